"""The README's Python example is examples/sweep.py, as written, and it runs:
headless (MPLBACKEND=Agg), it prints the error at each sample count and
saves sweep.png; the error falls as samples are added."""
import os
import re
import subprocess
import sys

ROOT = os.environ["DIRT_SOURCE_ROOT"]


def test_readme_shows_the_example():
    with open(os.path.join(ROOT, "README.md"), encoding="utf-8") as f:
        blocks = re.findall(r"```python\n(.*?)```", f.read(), re.S)
    with open(os.path.join(ROOT, "examples", "sweep.py"), encoding="utf-8") as f:
        example = f.read()
    assert example in blocks, "README.md must show examples/sweep.py as it is"


def test_the_example_runs(tmp_path):
    out = subprocess.run([sys.executable, os.path.join(ROOT, "examples", "sweep.py")],
                         cwd=tmp_path, capture_output=True, text=True, timeout=240)
    assert out.returncode == 0, out.stderr
    errors = [float(line.split()[-1]) for line in out.stdout.splitlines()]
    assert len(errors) == 6
    assert errors[-1] < errors[0] / 4  # about 1/32 at 32 spp
    png = (tmp_path / "sweep.png").read_bytes()
    assert png[:8] == b"\x89PNG\r\n\x1a\n" and len(png) > 5000
