"""safe_yaml: PyYAML's safe values, within bounds, whichever parser (libyaml or Python) reads them."""

from __future__ import annotations

import pytest
import yaml
from hypothesis import given
from hypothesis import strategies as st

from marm_setup.safe_yaml import MAX_DEPTH, YamlLimitError, load_yaml, load_yaml_lines

scalars = st.none() | st.booleans() | st.integers() | st.floats(allow_nan=False) | st.text(max_size=12)
documents = st.recursive(
    scalars,
    lambda inner: st.lists(inner, max_size=4) | st.dictionaries(st.text(max_size=8), inner, max_size=4),
    max_leaves=30,
)


@given(documents, st.booleans())
def test_values_are_safe_loads(data, flow):
    text = yaml.safe_dump(data, default_flow_style=flow)
    assert load_yaml(text) == yaml.safe_load(text)


@pytest.mark.parametrize(
    "text",
    [
        "a: " + "[" * (MAX_DEPTH + 1) + "]" * (MAX_DEPTH + 1) + "\n",  # flow, below libyaml's own bound
        "x: " + "[" * 50_000 + "]" * 50_000 + "\n",  # beyond it
        "".join(" " * (2 * i) + f"k{i}:\n" for i in range(MAX_DEPTH + 1)) + " " * (2 * MAX_DEPTH + 2) + "v\n",
    ],
    ids=["flow", "flow-50000", "block"],
)
def test_too_deep_is_refused_with_its_bound(text):
    with pytest.raises(YamlLimitError, match=f"nested deeper than {MAX_DEPTH}"):
        load_yaml(text)


def test_as_deep_as_the_bound_loads():
    text = "[" * MAX_DEPTH + "1" + "]" * MAX_DEPTH
    value = load_yaml(text)
    for _ in range(MAX_DEPTH - 1):
        value = value[0]
    assert value == [1]


def test_lines_of_keys_and_items():
    data, lines = load_yaml_lines("a:\n  b: 1\n  c:\n    - x\n    - y\n")
    assert data == {"a": {"b": 1, "c": ["x", "y"]}}
    assert lines == {("a",): 1, ("a", "b"): 2, ("a", "c"): 3, ("a", "c", 0): 4, ("a", "c", 1): 5}


def test_a_syntax_error_is_a_yaml_error_with_its_line():
    with pytest.raises(yaml.MarkedYAMLError) as caught:
        load_yaml("a: 1\nb: [1, 2\n")
    assert caught.value.problem_mark is not None and caught.value.problem_mark.line >= 1
