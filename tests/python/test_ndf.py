"""smithlab's NDFs from Python: the same numbers as the command line (to the last bit, where the same code runs),
against closed forms and independent integrations elsewhere, NumPy's broadcasting and dtype rules, and bad input
raising ValueError with the command line's message."""
import csv
import io
import math

import numpy as np
import pytest

import smithlab


def read_csv(text):
    return list(csv.DictReader(io.StringIO(text)))


@pytest.mark.parametrize("spec", ["ggx(alpha=0.2)", "beckmann(alpha=0.05)", "gtr(alpha=0.3, gamma=1.5)",
                                  "student(alpha=0.3, gamma=3)", "blinn(n=40)", "abc(b=20, c=1.5)"])
@pytest.mark.parametrize("method", ["auto", "quadrature", "quadrature2d", "fixed", "table"])
def test_lambda_and_g1_are_the_command_lines_bits(cli, spec, method):
    n = smithlab.ndf(spec)
    rows = read_csv(cli("eval", "--ndf", spec, "--mu-range", "log:0.003:300:23", "--method", method))
    mu = np.array([float(r["mu"]) for r in rows])
    assert n.Lambda(mu, method=method).tolist() == [float(r["lambda"]) for r in rows]
    assert n.G1(mu, method=method).tolist() == [float(r["g1"]) for r in rows]


@pytest.mark.parametrize("method", ["family", "dimov-spline", "closed", "spline", "interp-akima-g1-k4"])
def test_gtr_methods_are_the_command_lines_bits(cli, method):
    n = smithlab.ndf("gtr", alpha=0.3, gamma=2.0)
    rows = read_csv(cli("eval", "--ndf", n.spec, "--theta-range", "0:180:37", "--method", method,
                        "--downward", "hammon"))
    mu = np.array([float(r["mu"]) for r in rows])
    assert n.Lambda(mu, method=method, downward="hammon").tolist() == [float(r["lambda"]) for r in rows]
    assert n.G1(mu, method=method).tolist() == [float(r["g1"]) for r in rows]


def test_gsl_backend_and_tolerance_are_the_command_lines(cli):
    n = smithlab.ndf("gtr(alpha=0.1, gamma=0.5)")
    out = read_csv(cli("eval", "--ndf", n.spec, "--mu-range", "0.1:3:4", "--method", "quadrature", "--backend",
                       "gsl", "--tolerance", "1e-8"))
    got = n.Lambda([float(r["mu"]) for r in out], method="quadrature", backend="gsl", tolerance=1e-8)
    assert got.tolist() == [float(r["lambda"]) for r in out]


def test_closed_forms_by_their_own_formulas():
    # GGX (Walter 2007 eq. 72): Lambda = (-1 + sqrt(1 + x)) / 2 = x / (2 (1 + sqrt(1 + x))), x = (alpha / mu)^2
    # (the second form free of cancellation), and its D and slope density.
    alpha, mu = 0.37, np.geomspace(1e-3, 1e3, 41)
    ggx = smithlab.ndf("ggx", alpha=alpha)
    x = (alpha / mu) ** 2
    exact = x / (2.0 * (1.0 + np.sqrt(1.0 + x)))
    for method in ["quadrature", "quadrature2d", "fixed"]:
        assert np.allclose(ggx.Lambda(mu, method=method), exact, rtol=1e-12, atol=0)
    c = np.linspace(0.05, 1.0, 20)
    assert np.allclose(ggx.D(c), alpha**2 / (np.pi * ((alpha**2 - 1) * c * c + 1) ** 2), rtol=1e-14)
    x, y = np.meshgrid(np.linspace(-2, 2, 9), np.linspace(-1, 3, 7))
    assert np.allclose(ggx.P22(x, y), alpha**2 / (np.pi * (alpha**2 + x * x + y * y) ** 2), rtol=1e-14)
    # Beckmann's Lambda through erfc (Walter 2007 eq. 25), at a = mu / alpha <= 4, where its two terms cancel by
    # less than a factor 2 a^2 (beyond it the reference, not the engine, loses the digits).
    b = smithlab.ndf("beckmann(alpha=0.2)")
    a = mu[mu <= 0.8] / 0.2
    lam = np.array([(math.exp(-t * t) / (t * math.sqrt(math.pi)) - math.erfc(t)) / 2 for t in a])
    assert np.allclose(b.Lambda(0.2 * a, method="quadrature"), lam, rtol=1e-12, atol=0)


def test_p2_and_d_integrate_as_their_definitions_say():
    n = smithlab.ndf("gtr(alpha=0.4, gamma=1.5)")
    # P2(q) = integral of P22(p, q) dp, by the trapezoid rule in p = sinh(u) (independent of the engine's route).
    u = np.linspace(-30, 30, 20001)
    p = np.sinh(u)
    for q in [0.0, 0.3, 2.0]:
        ref = np.trapz(n.P22(p, q) * np.cosh(u), u)
        assert n.P2(q) == pytest.approx(ref, rel=1e-7)
    # D is normalized: 2 pi integral D cos sin dtheta = 1 (Walter 2007 eq. 4).
    t = np.linspace(0, np.pi / 2, 200001)
    assert 2 * np.pi * np.trapz(n.D(np.cos(t)) * np.cos(t) * np.sin(t), t) == pytest.approx(1.0, rel=1e-7)


def test_g2_forms_and_broadcasting():
    n = smithlab.ndf("ggx(alpha=0.5)")
    mi, mo = np.array([[0.3], [1.0], [-2.0]]), np.array([0.1, 0.5, 2.0, np.inf])
    g2 = n.G2(mi, mo)
    assert g2.shape == (3, 4) and g2.dtype == np.float64
    li, lo = n.Lambda(np.abs(mi)), n.Lambda(np.abs(mo))
    same = 1.0 / (1.0 + li + lo)
    assert np.allclose(g2[:2], same[:2], rtol=1e-15)
    # across the surface: Beta(1 + Lambda_i, 1 + Lambda_o) (Heitz 2014)
    beta = math.gamma(1 + li[2, 0]) * np.array([math.gamma(1 + x) for x in lo]) / np.array(
        [math.gamma(2 + li[2, 0] + x) for x in lo])
    assert np.allclose(g2[2], beta, rtol=1e-12)
    g1 = n.G1(np.abs(mi)) * n.G1(np.abs(mo))
    assert np.allclose(n.G2(mi, mo, form="uncorrelated"), g1, rtol=1e-15)
    for i in range(3):
        for j in range(4):
            assert g2[i, j] == n.G2(float(mi[i, 0]), float(mo[j]))
    # three dimensions against two, one of them a strided view
    x, y = np.random.default_rng(3).random((2, 1, 6))[:, :, ::2], np.random.default_rng(4).random((4, 1))
    g = n.G2(x, y)
    assert g.shape == (2, 4, 3)
    assert all(g[i, j, k] == n.G2(x[i, 0, k], y[j, 0]) for i in range(2) for j in range(4) for k in range(3))


def test_scalars_lists_dtypes_and_shapes():
    n = smithlab.ndf("gtr(alpha=0.3, gamma=1.5)")
    assert isinstance(n.G1(0.5), float)
    assert isinstance(n.G1(np.float32(0.5)), float)
    assert n.G1(np.float32(0.5)) == n.G1(float(np.float32(0.5)))
    assert n.G1([1, 2]).dtype == np.float64  # integers read as numbers
    a = np.arange(12, dtype=np.float32).reshape(3, 4) / 4 + 0.1
    out = n.G1(a)
    assert out.shape == (3, 4) and out.dtype == np.float64
    assert out[1, 2] == n.G1(float(a[1, 2]))
    assert n.G1(a.T).tolist() == out.T.tolist()  # a non-contiguous view
    assert n.G1(np.array([])).shape == (0,)
    assert n.G1(np.array(0.25)) == n.G1(0.25)
    # the special directions (smith.hpp): grazing, normal, below
    assert n.Lambda([0.0, np.inf]).tolist() == [np.inf, 0.0]
    assert n.G1([0.0, np.inf, -0.5]).tolist() == [0.0, 1.0, n.G1(0.5)]
    assert n.Lambda(-0.5) == -1.0 - n.Lambda(0.5)
    assert n.Lambda(-0.5, downward="hammon") == -n.Lambda(0.5)
    with pytest.raises(ValueError, match="could not be broadcast together with shapes \\(2,\\) \\(3,\\)"):
        n.G2([1.0, 2.0], [1.0, 2.0, 3.0])


def test_ndf_objects():
    n = smithlab.ndf("gtr", alpha=0.3, gamma=1.5)
    assert n.spec == "gtr(alpha=0.3, gamma=1.5)" and n.family == "gtr"
    assert n.params == {"alpha": 0.3, "gamma": 1.5}
    assert repr(n) == "smithlab.ndf('gtr(alpha=0.3, gamma=1.5)')"
    names = [d["name"] for d in smithlab.list()]
    assert {"ggx", "beckmann", "gtr", "student", "tabulated"} <= set(names)
    assert all(smithlab.ndf(e).spec for d in smithlab.list() for e in d["examples"][:1])
    assert ("family", ) == tuple(m for m, _ in smithlab.methods() if m == "family")


@pytest.mark.parametrize("call, message", [
    (lambda: smithlab.ndf("gtr(alpha=-1, gamma=1)"), "gtr: alpha must be in [1e-50, 1], got -1"),
    (lambda: smithlab.ndf("gtr", alpha=0.3, gamma=-2), "gamma"),
    (lambda: smithlab.ndf("ggx(alpha=nan)"), "alpha"),
    (lambda: smithlab.ndf("nosuch(alpha=1)"), "nosuch"),
    (lambda: smithlab.ndf("ggx", beta=1), "beta"),
    (lambda: smithlab.ndf("ggx(alpha=0.3)").G1([0.5, np.nan]), "mu is NaN"),
    (lambda: smithlab.ndf("ggx(alpha=0.3)").D(np.nan), "cos_theta_m must be in [-1, 1], got nan"),
    (lambda: smithlab.ndf("ggx(alpha=0.3)").D([0.5, 1.5]), "cos_theta_m must be in [-1, 1], got 1.5"),
    (lambda: smithlab.ndf("ggx(alpha=0.3)").G1("abc"), "could not convert string to float: 'abc'"),
    (lambda: smithlab.ndf("gtr", alpha="0.3", gamma=1), "gtr: alpha takes a number, got '0.3'"),
    (lambda: smithlab.ndf("gtr", alpha=None, gamma=1), "gtr: alpha takes a number, got None"),
    (lambda: smithlab.ndf("tabulated", file=3), "tabulated: file takes text, got 3"),
    (lambda: smithlab.ndf("ggx(alpha=0.3)").Lambda(1, method="nosuch"), "nosuch"),
    (lambda: smithlab.ndf("ggx(alpha=0.3)").Lambda(1, backend="scipy"), "scipy"),
    (lambda: smithlab.ndf("ggx(alpha=0.3)").Lambda(1, tolerance=0.5), "tolerance must be in [1e-15, 0.1], got 0.5"),
    (lambda: smithlab.ndf("ggx(alpha=0.3)").Lambda(1, downward="up"), "up"),
    (lambda: smithlab.ndf("ggx(alpha=0.3)").Lambda(1, method="family"), "family"),
    (lambda: smithlab.ndf("ggx(alpha=0.3)").G2(1, 1, form="separable"), "form must be"),
    (lambda: smithlab.family_G1([0.3, 2.0], 1.5, 1.0), "family: alpha[1] must be in [1e-4, 1], got 2"),
    (lambda: smithlab.family_G1(0.3, 1.5, [1.0, np.nan]), "mu[1]"),
    (lambda: smithlab.family_G1(np.where(np.arange(10000) == 9000, 2.0, 0.3), 1.5, 1.0),
     "family: alpha[9000] must be in [1e-4, 1], got 2"),  # named by its place in the whole array
    (lambda: smithlab.sample(smithlab.ndf("ggx(alpha=0.3)"), "nosuch", 3), "nosuch"),
    (lambda: smithlab.sample(smithlab.ndf("ggx(alpha=0.3)"), "vndf", 3, seed=-1), "seed"),
    (lambda: smithlab.sample(smithlab.ndf("ggx(alpha=0.3)"), "vndf", 3, theta_i=200), "theta_i"),
    (lambda: smithlab.sample(smithlab.ndf("ggx(alpha=0.3)"), "vndf", -3), "n must be >= 0"),
    (lambda: smithlab.tabulated("t_bad_len", theta_deg=[0, 10, 20], D=[1, 2]), "got shapes (3,) and (2,)"),
    (lambda: smithlab.tabulated("t_2d", cos_theta=np.ones((10, 10)), D=np.ones((10, 10))),
     "cos_theta and D must be 1-D arrays of one length, got shapes (10,10) and (10,10)"),
    (lambda: smithlab.tabulated("t_bad_both", D=[1, 2, 3]), "exactly one of"),
    (lambda: smithlab.tabulated("t_bad_d", theta_deg=[0, 10, 20, 30], D=[0.3, -1, 0.2, 0.1]), "t_bad_d:3"),
    (lambda: smithlab.tabulated("ggx", theta_deg=[0, 10, 20], D=[1, 2, 3]), "the name 'ggx' is taken"),
    (lambda: smithlab.from_function(lambda c: 1.0, "t_bad_rows", rows=2), "rows must be an integer >= 3"),
])
def test_bad_input_raises_naming_the_item(call, message):
    with pytest.raises(ValueError) as e:
        call()
    assert message in str(e.value)


def test_family_stream_against_closed_forms():
    alpha, gamma = np.meshgrid(np.geomspace(1e-3, 1, 7), [1.0, 2.0, 3.0, 4.0])
    mu = np.geomspace(1e-3, 1e3, 13)[:, None, None]
    got = smithlab.family_G1(alpha, gamma, mu)
    assert got.shape == (13, 4, 7)
    worst = 0.0
    for i, g in enumerate([1.0, 2.0, 3.0, 4.0]):
        for j, a in enumerate(alpha[0]):
            ref = smithlab.ndf("gtr", alpha=float(a), gamma=g).G1(mu[:, 0, 0], method="closed")
            worst = max(worst, np.abs(got[:, i, j] - ref).max())
    assert worst <= 9.5e-7  # the family evaluator's stated bound on |dG1|


@pytest.mark.parametrize("family, bound", [("ggx", 2e-9), ("beckmann", 1e-6)])
def test_a_d_written_in_python_reproduces_the_closed_form(family, bound):
    # D as a Python function; its Lambda against the registered NDF's closed form over mu in [0.01 alpha, 1000
    # alpha], where Lambda > 1e-8 (Beckmann's falls off like exp(-mu^2 / alpha^2)): the figures from_function states.
    for alpha in [1e-3, 3e-3, 0.01, 0.03, 0.1, 0.3, 0.5, 1.0]:
        if family == "ggx":
            def D(c, a=alpha):
                return a * a / (np.pi * ((a * a - 1) * c * c + 1) ** 2)
        else:
            def D(c, a=alpha):
                return np.exp(-(1 - c * c) / (c * c * a * a)) / (np.pi * a * a * c**4)
        with np.errstate(divide="ignore", over="ignore", invalid="ignore"):
            n = smithlab.from_function(D, f"py_{family}_{str(alpha).replace('.', '_').replace('-', '_')}")
        mu = np.geomspace(0.01 * alpha, 1000 * alpha, 201)
        ref = smithlab.ndf(family, alpha=alpha).Lambda(mu)
        seen = ref > 1e-8
        assert np.abs(n.Lambda(mu[seen]) / ref[seen] - 1).max() < bound, alpha
        # the family takes a roughness: scale 2 stretches the slopes, the closed form's NDF of alpha 2 alpha
        if family == "ggx" and alpha <= 0.5:
            wide = smithlab.ndf(f"{n.family}(scale=2)")
            assert np.abs(wide.Lambda(mu) / smithlab.ndf(family, alpha=2 * alpha).Lambda(mu) - 1).max() < bound


def test_a_name_made_again_takes_the_new_table():
    first = smithlab.from_function(lambda c: 0.25 / (np.pi * ((0.25 - 1) * c * c + 1) ** 2), "py_remade")
    second = smithlab.from_function(lambda c: 1 / (np.pi * c**0), "py_remade")  # GGX of alpha 1
    assert first.Lambda(0.5) == pytest.approx(smithlab.ndf("ggx(alpha=0.5)").Lambda(0.5), rel=1e-9)
    assert second.Lambda(0.5) == pytest.approx(smithlab.ndf("ggx(alpha=1)").Lambda(0.5), rel=1e-9)
    assert smithlab.ndf("py_remade").Lambda(0.5) == second.Lambda(0.5)
    assert first.Lambda(0.5) != second.Lambda(0.5)  # an NDF made before keeps its own table


def test_a_function_with_a_branch_is_called_row_by_row():
    def D(c):  # "the truth value of an array is ambiguous" on an array
        return 0.25 / (math.pi * ((0.25 - 1) * c * c + 1) ** 2) if c > 0 else 0.0

    n = smithlab.from_function(D, "py_branchy")
    assert n.Lambda(0.7) == pytest.approx(smithlab.ndf("ggx(alpha=0.5)").Lambda(0.7), rel=1e-9)


def test_a_scalar_python_function_is_called_row_by_row():
    calls = []

    def D(c):
        calls.append(c)
        c = float(c)  # an array of many values raises TypeError here
        return 0.25 / (math.pi * ((0.25 - 1) * c * c + 1) ** 2)

    n = smithlab.from_function(D, "py_scalar_ggx", rows=512)
    assert len(calls) == 1 + 512
    assert n.Lambda(0.7) == pytest.approx(smithlab.ndf("ggx(alpha=0.5)").Lambda(0.7), rel=1e-7)


@pytest.mark.parametrize("sampler, spec", [("vndf", "gtr(alpha=0.3, gamma=1.5)"), ("vndf-ggx", "ggx(alpha=0.4)"),
                                           ("dcos", "beckmann(alpha=0.2)"), ("vndf-mixture", "student(alpha=0.3, gamma=3)")])
def test_samplers_are_the_command_lines_bits(cli, sampler, spec):
    normals, pdf = smithlab.sample(smithlab.ndf(spec), sampler, 50, theta_i=30, seed=7)
    rows = read_csv(cli("sample", "--ndf", spec, "--sampler", sampler, "--n", "50", "--theta-i", "30", "--seed", "7"))
    assert normals.shape == (50, 3) and pdf.shape == (50,)
    assert normals.tolist() == [[float(r["x"]), float(r["y"]), float(r["z"])] for r in rows]
    assert pdf.tolist() == [float(r["pdf"]) for r in rows]
    assert [s for s, _ in smithlab.samplers()].count(sampler) == 1


def test_a_d_written_in_python_walks_like_the_closed_form():
    # The walk on GGX written in Python against the registered GGX: each order's albedo within 4 combined standard
    # errors (different hit-normal routes: the same law, other random numbers).
    def D(c):
        return 0.25 / (np.pi * ((0.25 - 1) * c * c + 1) ** 2)

    mine = smithlab.from_function(D, "py_ggx_walked")
    a = smithlab.trace(mine, "mirror", theta_i=60.0, walks=200_000, seed=3)
    b = smithlab.trace(smithlab.ndf("ggx(alpha=0.5)"), "mirror", theta_i=60.0, walks=200_000, seed=4)
    reflection, every = a["hemispheres"].index("reflection"), a["components"].index("all")
    for order in range(5):
        x, y = a["albedo"][reflection, order, every], b["albedo"][reflection, order, every]
        se = np.hypot(a["stderr"][reflection, order, every], b["stderr"][reflection, order, every])
        assert abs(x - y) <= 4 * se, (a["orders"][order], x, y, se)
    assert a["albedo"][reflection, 0, every] > 0.5
