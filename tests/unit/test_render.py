"""render's filters: numbers and strings that YAML (PyYAML, as rosparam uses it) reads back as written."""

from __future__ import annotations

import pytest
import yaml

from marm_setup.templating import fmt_float, yaml_str


@pytest.mark.parametrize("value", [0.0, -0.0, 1.0, 2, 0.005, -0.4487, 1e-05, 2.5e-07, 1e16, -3.2e20, 1 / 3])
def test_fmt_float_reads_back_as_the_same_float(value):
    text = fmt_float(value)
    assert "." in text and text != "-0.0"
    parsed = yaml.safe_load(f"x: {text}")["x"]
    assert isinstance(parsed, float) and parsed == float(value), text


def test_fmt_float_refuses_non_finite_numbers():
    for value in (float("inf"), float("nan")):
        with pytest.raises(ValueError):
            fmt_float(value)


@pytest.mark.parametrize("text", ["on", "yes", "null", "1e3", "0.5", "arm", "a: b", "#x"])
def test_yaml_str_reads_back_as_the_same_string(text):
    assert yaml.safe_load(f"x: {yaml_str(text)}")["x"] == text
