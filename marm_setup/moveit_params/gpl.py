"""generate_parameter_library YAML files as table rows: every leaf mapping with a `type` is a
parameter; the root key is the generated code's C++ namespace, not part of a name
(PickNikRobotics/generate_parameter_library parse_yaml.py: `nested_name_list[1:]`), nested
mappings without `type` are sub-namespaces, and `__map_<key>` a mapping over the values of
`<key>` (one entry per name listed there)."""

from __future__ import annotations

from collections.abc import Iterator

import yaml

# validators whose arguments the rule checks (generate_parameter_library_py validators
# `gt<>`, `gt_eq<>`, `lt<>`, `lt_eq<>`, `bounds<>`, `one_of<>`); others are kept as written
VALIDATOR_SUFFIX = "<>"


def gpl_rows(text: str, path: str, prefix: str, node: str) -> list[dict]:
    """Rows of one gpl file, each name `prefix` + its dotted path below the root key."""
    root = yaml.compose(text)
    if not isinstance(root, yaml.MappingNode) or not root.value:
        return []
    _, body = root.value[0]
    return [_row(node, prefix + name, spec, f"{path}:{line}") for name, spec, line in _leaves(body, "")]


def _leaves(node: yaml.Node, prefix: str) -> Iterator[tuple[str, dict, int]]:
    if not isinstance(node, yaml.MappingNode):
        return
    for key_node, value in node.value:
        key = str(key_node.value)
        name = f"<{key[len('__map_') :]}>" if key.startswith("__map_") else key
        data = yaml.safe_load(yaml.serialize(value))
        if isinstance(data, dict) and "type" in data:
            yield prefix + name, data, key_node.start_mark.line + 1
        else:
            yield from _leaves(value, f"{prefix}{name}.")


def _row(node: str, name: str, spec: dict, source: str) -> dict:
    row: dict = {"node": node, "name": name, "type": str(spec["type"])}
    if "default_value" in spec:
        row["default"] = spec["default_value"]
    validation = {str(k).removesuffix(VALIDATOR_SUFFIX): v for k, v in (spec.get("validation") or {}).items()}
    if validation:
        row["validation"] = validation
    if spec.get("read_only"):
        row["read_only"] = True
    row["on_wrong"] = "throws"  # the ParamListener's declare_parameter refuses it: the node stops
    row["source"] = source
    return row
