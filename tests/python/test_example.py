"""The example experiments/python/examples/g1_and_albedo.py runs and draws both figures."""
import os
import pathlib
import subprocess
import sys

EXAMPLE = pathlib.Path(__file__).resolve().parents[2] / "experiments" / "python" / "examples" / "g1_and_albedo.py"


def test_the_example_draws_both_figures(tmp_path):
    subprocess.run([sys.executable, str(EXAMPLE), str(tmp_path / "figures")], check=True, env=dict(os.environ),
                   capture_output=True, text=True, timeout=120)
    for name in ["g1_gtr.png", "albedo_by_order.png"]:
        data = (tmp_path / "figures" / name).read_bytes()
        assert data[:8] == b"\x89PNG\r\n\x1a\n", name
        assert len(data) > 10_000, f"{name}: {len(data)} bytes"
