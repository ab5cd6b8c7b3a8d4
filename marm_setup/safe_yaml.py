"""YAML input with bounds: every YAML file we read goes through `load_yaml`.

PyYAML's `safe_load` is safe from code but not from work: its composer recurses once per nesting
level (50,000 `[` is a RecursionError, or a crash in libyaml's composer), aliases let a few
hundred bytes stand for billions of nodes (a MemoryError in whoever walks the result), and an
alias may point into itself. Here a document is refused, as a `yaml.YAMLError` so callers report
it as any malformed YAML, when it is larger than MAX_BYTES, nested deeper than MAX_DEPTH (counted
on the parser's events, which need no recursion, before anything is composed), expands (aliases
followed) to more than MAX_NODES nodes, or refers to itself.

Parsing and composing are libyaml's (PyYAML's C loader, about 8 times faster than its pure-Python
one: validate reads a few dozen YAML files per package) where PyYAML was built with it; the
constructors and resolvers stay PyYAML's Python ones, so the values are safe_load's.
"""

from __future__ import annotations

from typing import Any

import yaml

MAX_BYTES = 16 * 1024 * 1024
MAX_DEPTH = 200  # a MoveIt config nests about 8 deep
MAX_NODES = 1_000_000


class YamlLimitError(yaml.YAMLError):
    """A document over one of the bounds; `problem` says which (as PyYAML's errors do)."""

    def __init__(self, problem: str):
        super().__init__(problem)
        self.problem = problem
        self.problem_mark = None


# libyaml's parser and composer with PyYAML's safe constructors, else PyYAML's pure-Python loader
_SAFE_LOADER: type = yaml.CSafeLoader if yaml.__with_libyaml__ else yaml.SafeLoader
_OPENING = (yaml.MappingStartEvent, yaml.SequenceStartEvent)
_CLOSING = (yaml.MappingEndEvent, yaml.SequenceEndEvent)


class BoundedSafeLoader(_SAFE_LOADER):
    """PyYAML's safe loader within the bounds above (subclass it to add constructors); the
    nesting bound is `check_depth`'s, run on the text first."""

    def get_single_node(self):
        node = super().get_single_node()
        if node is not None:
            _check_expanded_size(node)
        return node


def check_depth(text: str) -> None:
    """Refuse `text` nested deeper than MAX_DEPTH, from the parser's events (no recursion)."""
    depth = 0
    try:
        for event in yaml.parse(text, Loader=_SAFE_LOADER):
            if isinstance(event, _OPENING):
                depth += 1
                if depth > MAX_DEPTH:
                    break
            elif isinstance(event, _CLOSING):
                depth -= 1
    except yaml.MarkedYAMLError as exc:  # libyaml's scanner looks ahead into flow nesting
        if "maximum nesting depth" not in str(exc.problem):  # and stops at its own bound, 1000
            raise
        depth = MAX_DEPTH + 1
    if depth > MAX_DEPTH:
        raise YamlLimitError(f"nested deeper than {MAX_DEPTH} levels")


def _check_expanded_size(root: yaml.Node) -> None:
    """Count nodes as the constructed data will hold them (an alias counts its whole target)."""
    sizes: dict[int, int] = {}
    open_nodes: set[int] = set()
    stack: list[tuple[yaml.Node, bool]] = [(root, False)]
    while stack:
        node, children_done = stack.pop()
        key = id(node)
        if key in sizes:
            continue
        kids = _children(node)
        if children_done:
            open_nodes.discard(key)
            sizes[key] = 1 + sum(sizes[id(k)] for k in kids)
            if sizes[key] > MAX_NODES:
                raise YamlLimitError(f"expands to more than {MAX_NODES:,} values (aliases followed)")
            continue
        if key in open_nodes:
            raise YamlLimitError("an alias refers to a node that contains it")
        open_nodes.add(key)
        stack.append((node, True))
        stack.extend((k, False) for k in kids if id(k) not in sizes)
    return None


def _children(node: yaml.Node) -> list[yaml.Node]:
    if isinstance(node, yaml.MappingNode):
        return [n for pair in node.value for n in pair]
    if isinstance(node, yaml.SequenceNode):
        return list(node.value)
    return []


class UniqueKeyLoader(BoundedSafeLoader):
    """A BoundedSafeLoader that refuses a mapping naming a key twice (PyYAML keeps the last one
    silently): for our own files, where a repeated key is a mistake."""

    def construct_mapping(self, node, deep=False):
        if isinstance(node, yaml.MappingNode):
            self.flatten_mapping(node)  # merge keys (`<<: *anchor`) first, as SafeLoader does
        seen: set = set()
        for key_node, _ in node.value:
            key = self.construct_object(key_node, deep=True)
            if not isinstance(key, str | int | float | bool):
                continue  # an unhashable key is PyYAML's to refuse
            if (type(key), key) in seen:  # 1 and true are different keys
                raise yaml.constructor.ConstructorError(
                    None, None, f"key '{key}' given twice", key_node.start_mark
                )
            seen.add((type(key), key))
        return super().construct_mapping(node, deep)


def load_yaml(text: str, loader_class: type[BoundedSafeLoader] = BoundedSafeLoader) -> Any:
    """`yaml.safe_load(text)` within the bounds above; raises yaml.YAMLError (also for a value no
    Python number holds: an integer of more than 4300 digits)."""
    return load_yaml_lines(text, loader_class)[0]


# A value's key path in a document: mapping keys as written (str), sequence indexes (int).
KeyPath = tuple[str | int, ...]


def load_yaml_lines(
    text: str, loader_class: type[BoundedSafeLoader] = BoundedSafeLoader
) -> tuple[Any, dict[KeyPath, int]]:
    """(`load_yaml(text)`, the 1-based line of every key and list item by its key path), within
    the same bounds; a value an alias repeats has the line of its first occurrence only."""
    if len(text) > MAX_BYTES:
        raise YamlLimitError(f"larger than {MAX_BYTES // (1024 * 1024)} MiB")
    check_depth(text)
    loader = loader_class(text)
    try:
        node = loader.get_single_node()
        data = loader.construct_document(node) if node is not None else None
    except (ValueError, OverflowError) as exc:  # a constructor's int()/float() on an absurd scalar
        raise YamlLimitError(f"a value no number can hold ({' '.join(str(exc).split())[:80]})") from None
    finally:
        loader.dispose()
    return data, _lines(node)


def _lines(root: yaml.Node | None) -> dict[KeyPath, int]:
    out: dict[KeyPath, int] = {}
    seen: set[int] = set()
    stack: list[tuple[yaml.Node, KeyPath]] = [(root, ())] if root is not None else []
    while stack:
        node, path = stack.pop()
        if id(node) in seen:
            continue
        seen.add(id(node))
        if isinstance(node, yaml.MappingNode):
            for key, value in node.value:
                if isinstance(key, yaml.ScalarNode) and key.tag != "tag:yaml.org,2002:merge":
                    out.setdefault((*path, str(key.value)), key.start_mark.line + 1)
                    stack.append((value, (*path, str(key.value))))
        elif isinstance(node, yaml.SequenceNode):
            for i, item in enumerate(node.value):
                out.setdefault((*path, i), item.start_mark.line + 1)
                stack.append((item, (*path, i)))
    return out
