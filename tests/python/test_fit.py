"""The fitter's pieces from Python: the diffuse models (the values the fit's tables hold), a fit's constants read from
its output directory, and the compensation tables, against a tiny `smithlab fit` run; bad input raising ValueError
naming the item."""
import csv
import math
import pathlib
import shutil

import numpy as np
import pytest

import smithlab

# The fit tests' tiny scene (tests/fit_tiny_scene.toml: two models, GGX, a few hundred walks a point), with a second
# NDF family that has a parameter column of its own and one compensation table per family and alpha, 4 cosines: well
# under a second.
TINY_SCENE = (pathlib.Path(__file__).resolve().parents[1] / "fit_tiny_scene.toml").read_text() + """[[ndf]]
family = "gtr"
gamma = [1.5]
[compensation]
alpha = [0.5, 1.0]
cosines = 4
refine = 2
g2 = ["separable"]
furnace_alpha = [0.5]
furnace_theta = [0.0]
furnace_walks = 100
"""


def rows(path):
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


@pytest.fixture(scope="module")
def fit_dir(cli, tmp_path_factory):
    d = tmp_path_factory.mktemp("fit")
    (d / "scene.toml").write_text(TINY_SCENE)
    cli("fit", str(d / "scene.toml"), "-o", str(d / "out"), "--threads", "2")
    return d / "out"


def test_read_fit_is_the_files_constants(fit_dir):
    values, errors = smithlab.read_fit(fit_dir), smithlab.read_fit(str(fit_dir), stderr=True)
    table = rows(fit_dir / "constants.csv")
    assert len(table) == 2
    assert values == {"fujii": {"ggx": {"sigma_scale": float(table[0]["value"])},
                                "gtr(gamma=1.5)": {"sigma_scale": float(table[1]["value"])}}}
    for row in table:
        model = row["model"].removesuffix("-fitted")
        assert values[model][row["ndf"]][row["parameter"]] == float(row["value"])
        assert errors[model][row["ndf"]][row["parameter"]] == float(row["stderr"])


def test_diffuse_f_times_cos_theta_o_is_the_fits_model_values(fit_dir):
    """validation.csv holds f |cos theta_o| of every model at its published constants and refitted."""
    fitted = smithlab.read_fit(fit_dir)
    table = rows(fit_dir / "validation.csv")
    assert len(table) > 20
    by_ndf = {}
    for row in table:
        by_ndf.setdefault(row["ndf"], []).append(row)
    assert sorted(by_ndf) == ["ggx", "gtr(gamma=1.5)"]
    for ndf, points in by_ndf.items():
        x = {k: np.array([float(p[k]) for p in points]) for k in ["theta_i", "theta_o", "phi", "alpha", "albedo"]}
        cos_o = np.cos(x["theta_o"] * (math.pi / 180.0))
        for column, model, constants in [("lambert", "lambert", None), ("fujii", "fujii", None),
                                         ("fujii-fitted", "fujii", list(fitted["fujii"][ndf].values()))]:
            f = smithlab.diffuse_f(model, x["theta_i"], x["theta_o"], x["phi"], x["alpha"], x["albedo"], constants)
            expected = np.array([float(p[column]) for p in points])
            assert np.allclose(f * cos_o, expected, rtol=1e-15, atol=0), (ndf, column)


def test_diffuse_f_broadcasts_and_knows_its_models():
    f = smithlab.diffuse_f("hammon-2017", np.array([[0.0], [30.0], [60.0]]), [10.0, 50.0], 0.0, 0.5, 0.8)
    assert f.shape == (3, 2) and f.dtype == np.float64 and np.all(f > 0.0)
    assert f[1, 1] == smithlab.diffuse_f("hammon-2017", 30.0, 50.0, 0.0, 0.5, 0.8)
    assert isinstance(smithlab.diffuse_f("lambert", 0.0, 0.0, 0.0, 0.5, 0.7), float)
    assert smithlab.diffuse_f("lambert", 10.0, 20.0, 30.0, 0.5, 0.7) == 0.7 / math.pi
    hammon = next(m for m in smithlab.diffuse_models() if m["name"] == "hammon-2017")
    assert f[0, 0] == smithlab.diffuse_f("hammon-2017", 0.0, 10.0, 0.0, 0.5, 0.8, hammon["published"])
    assert f[0, 0] != smithlab.diffuse_f("hammon-2017", 0.0, 10.0, 0.0, 0.5, 0.8, [0.9, 0.4, 0.5, 1.05, 0.3])


def test_diffuse_models_are_the_fitters_list(cli):
    listed = cli("fit", "--list-models").splitlines()
    models = smithlab.diffuse_models()
    assert [m["name"] for m in models] == listed[0::3]
    assert all(m["glsl"] for m in models)  # no "GLSL: has none" line: three lines a model
    for m, source, constants in zip(models, listed[1::3], listed[2::3]):
        assert m["description"] == source.strip()
        assert len(m["constants"]) == len(m["published"])
        if m["constants"]:
            words = constants.split()[1:]
            assert m["constants"] == words[0::3] and m["published"] == [float(v) for v in words[2::3]]
        else:
            assert "none" in constants


def test_compensation_is_the_fits_tables(fit_dir):
    table, averages = rows(fit_dir / "compensation.csv"), rows(fit_dir / "compensation_avg.csv")
    specs = [r["ndf"] for r in averages]
    assert len(specs) == 4
    for spec, avg in zip(specs, averages):
        c = smithlab.compensation(smithlab.ndf(spec), cosines=4, g2="separable")
        points = [r for r in table if r["ndf"] == spec]
        assert c["cos_theta"].tolist() == [float(r["cos_theta"]) for r in points]
        assert c["E"].tolist() == [float(r["E"]) for r in points]
        assert c["E_avg"] == float(avg["E_avg"])
        assert c["one_minus_E_avg"] == float(avg["one_minus_E_avg"])
        assert c["warp_scale"] == float(avg["warp_scale"])
    default = smithlab.compensation(smithlab.ndf("ggx(alpha=0.5)"))
    assert default["cos_theta"].shape == default["E"].shape == (48,) and default["E"][0] == 1.0


@pytest.mark.parametrize("call,message", [
    (lambda: smithlab.diffuse_f("velvet", 0, 0, 0, 0.5, 1), "unknown diffuse model 'velvet' (known: lambert,"),
    (lambda: smithlab.diffuse_f("fujii", 0, 0, 0, 0.5, 1, [1, 2]), "'fujii' takes 1 constant (sigma_scale), got 2"),
    (lambda: smithlab.diffuse_f("hammon-2017", 0, 0, 0, 0.5, 1, [1]),
     "'hammon-2017' takes 5 constants (rough_a, rough_b, rough_c, smooth, multi), got 1"),
    (lambda: smithlab.diffuse_f("lambert", 0, 0, 0, 0.5, 1, [1]), "'lambert' takes 0 constants (none), got 1"),
    (lambda: smithlab.diffuse_f("fujii", 0, 0, 0, 0.5, 1, [float("nan")]), "constant sigma_scale must be finite"),
    (lambda: smithlab.diffuse_f("fujii", 0, 0, 0, 0.5, 1, 2.0), "constants must be None or a sequence of numbers"),
    (lambda: smithlab.diffuse_f("fujii", 90, 0, 0, 0.5, 1), "theta_i must be in [0, 90) degrees, got 90"),
    (lambda: smithlab.diffuse_f("fujii", 0, [10, -1], 0, 0.5, 1), "theta_o must be in [0, 90) degrees, got -1"),
    (lambda: smithlab.diffuse_f("fujii", 0, 0, math.inf, 0.5, 1), "phi must be finite, got inf"),
    (lambda: smithlab.diffuse_f("fujii", 0, 0, 0, 0.0, 1), "alpha must be in (0, 1], got 0"),
    (lambda: smithlab.diffuse_f("fujii", 0, 0, 0, 0.5, 1.5), "albedo must be in [0, 1], got 1.5"),
    (lambda: smithlab.compensation(smithlab.ndf("ggx(alpha=0.5)"), cosines=1), "cosines must be in [2, 4096] (as the fit's [compensation] cosines), got 1"),
    (lambda: smithlab.compensation(smithlab.ndf("ggx(alpha=0.5)"), g2="smith"), "g2 must be 'height-correlated' or 'separable', got 'smith'"),
    (lambda: smithlab.read_fit("/nonexistent/fit"), "/nonexistent/fit/constants.csv: no such file"),
])
def test_bad_input_raises_value_error_naming_the_item(call, message):
    with pytest.raises(ValueError) as e:
        call()
    assert message in str(e.value)


@pytest.mark.parametrize("damage,message", [
    (lambda t: t.replace(",sigma_scale,0.", ",sigma_scale,x0.", 1), ":2: value"),
    (lambda t: t.replace("gtr(gamma=1.5),1.5,sigma_scale", "gtr(gamma=1.5),1.5,sigma", 1),
     ":3: model 'fujii' has no constant 'sigma' (its constants: sigma_scale)"),
    (lambda t: t.replace("fujii-fitted,gtr", "fujii,gtr", 1), ":3: model 'fujii' is not a fitted model's name"),
    (lambda t: t.replace("fujii-fitted,gtr", "velvet-fitted,gtr", 1), ":3: unknown diffuse model 'velvet'"),
    (lambda t: t.replace("stderr\n", "error\n", 1), ":1: no column 'stderr'"),
    (lambda t: t + "fujii-fitted,ggx,,sigma_scale,1,0.1\n", ":4: a second row of fujii-fitted on ggx, sigma_scale"),
    (lambda t: t + "fujii-fitted,ggx,sigma_scale,1,0.1\n", ":4: 5 fields where the header has 6"),
    (lambda t: t + "\"fujii-fitted,ggx\n", ":4: "),
    (lambda t: "", ": empty, not even a header"),
])
def test_a_damaged_constants_file_is_named_with_its_line(fit_dir, tmp_path, damage, message):
    text = (fit_dir / "constants.csv").read_text()
    damaged = damage(text)
    assert damaged != text
    (tmp_path / "constants.csv").write_text(damaged)
    with pytest.raises(ValueError) as e:
        smithlab.read_fit(tmp_path)
    assert str(tmp_path / "constants.csv") + message in str(e.value)


def test_read_fit_gives_the_models_order_whatever_the_files(tmp_path):
    # hammon-2017's five constants written in reverse: read back in the model's order, so that diffuse_f takes them.
    names = [m for m in smithlab.diffuse_models() if m["name"] == "hammon-2017"][0]["constants"]
    values = [0.85, 0.45, 0.55, 1.0, 0.15]
    lines = ["model,ndf,parameter,value,stderr"] + [f"hammon-2017-fitted,ggx,{n},{v},0.01"
                                                    for n, v in reversed(list(zip(names, values)))]
    (tmp_path / "constants.csv").write_text("\n".join(lines) + "\n")
    got = smithlab.read_fit(tmp_path)["hammon-2017"]["ggx"]
    assert list(got) == names and list(got.values()) == values
    f = smithlab.diffuse_f("hammon-2017", 30.0, 45.0, 90.0, 0.5, 0.8, constants=list(got.values()))
    assert f == smithlab.diffuse_f("hammon-2017", 30.0, 45.0, 90.0, 0.5, 0.8, constants=values)
    # one constant missing: refused, naming it
    (tmp_path / "constants.csv").write_text("\n".join(lines[:-1]) + "\n")
    with pytest.raises(ValueError, match="hammon-2017-fitted on ggx has no row for its constant rough_a"):
        smithlab.read_fit(tmp_path)
