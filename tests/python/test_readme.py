"""The README's Python example ("## From Python") runs as written."""

import os
import re

import numpy as np

import prtkit

README = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "README.md")


def test_the_readme_example_runs(tmp_path, monkeypatch):
    text = open(README).read()
    section = text[text.index("## From Python"):]
    code = re.search(r"```python\n(.*?)```", section, re.S).group(1)
    monkeypatch.chdir(tmp_path)
    scope = {}
    exec(compile(code, "README.md", "exec"), scope)
    image = prtkit.read_image(tmp_path / "cornell.png")
    assert image.shape == (240, 320, 3) and image.mean() > 0.01
    assert scope["T"].shape == (scope["mesh"].vertex_count, 9)
    assert np.isfinite(scope["radiance"]).all()
