"""The registry of validate's rules (marm_setup/validate/registry) is every rule id marm_setup/
emits, found by reading its source (an AST scan), each with its severities, what MoveIt does and
where; docs/rules.md is what `marm-setup rules --format markdown` writes now; and a validation's
findings keep to the registry at run time.

The scan finds a finding's rule id where it is made: the first argument of `error`, `warning`
and `Finding` (imported from marm_setup.findings, or a local alias such as `make = error if x
else warning`), and the `rule` argument (or its default) of any function taking one (setup/rules.py's
`r.link`, `r.group`, ...). An id is a string literal, a name bound to one (a local, a module
constant, or one imported such as findings.INTERNAL), a conditional of those, or
`f"{family}.suffix"` with `family` a parameter (runner.guarded): then every literal its callers
pass. `f.rule` re-emits an existing finding's id. Anything else fails `test_scan_reads_every_rule_id`.
"""

from __future__ import annotations

import ast
import difflib
from dataclasses import dataclass, field
from functools import cache
from pathlib import Path

import pytest
from typer.testing import CliRunner

from marm_setup.cli.app import app
from marm_setup.validate import (
    all_rules,
    allows,
    rule,
    rule_families,
    rule_family,
    rules_markdown,
    severity_of,
)
from tests.conftest import ROOT

PACKAGE = ROOT / "marm_setup"
DOC = ROOT / "docs" / "rules.md"
FINDINGS = "marm_setup.findings"
SEVERITIES = {"error": frozenset({"error"}), "warning": frozenset({"warning"})}


# -- the scan -----------------------------------------------------------------------------------


@dataclass
class Module:
    path: Path
    name: str
    tree: ast.Module
    parents: dict[ast.AST, ast.AST]
    imports: dict[str, tuple[str, str]]  # local name -> (module, name)

    def enclosing(self, node: ast.AST) -> ast.FunctionDef | None:
        while node in self.parents:
            node = self.parents[node]
            if isinstance(node, ast.FunctionDef):
                return node
        return None

    def where(self, node: ast.AST) -> str:
        return f"{self.path.relative_to(ROOT)}:{getattr(node, 'lineno', 0)}"


@dataclass
class Scan:
    emitted: dict[str, set[str]] = field(default_factory=dict)  # id -> severities
    sites: dict[str, str] = field(default_factory=dict)  # id -> one file:line making it
    unresolved: list[str] = field(default_factory=list)  # file:line: call


def _module(path: Path) -> Module:
    tree = ast.parse(path.read_text(encoding="utf-8"))
    parents = {child: node for node in ast.walk(tree) for child in ast.iter_child_nodes(node)}
    imports = {
        alias.asname or alias.name: (node.module, alias.name)
        for node in ast.walk(tree)
        if isinstance(node, ast.ImportFrom) and node.module
        for alias in node.names
    }
    name = ".".join(path.relative_to(ROOT).with_suffix("").parts).removesuffix(".__init__")
    return Module(path, name, tree, parents, imports)


def _params(fn: ast.FunctionDef) -> list[str]:
    names = [a.arg for a in (*fn.args.posonlyargs, *fn.args.args)]
    return names[1:] if names[:1] in (["self"], ["cls"]) else names


def _argument(call: ast.Call, index: int, name: str) -> ast.expr | None:
    if index < len(call.args) and not any(isinstance(a, ast.Starred) for a in call.args[: index + 1]):
        return call.args[index]
    return next((k.value for k in call.keywords if k.arg == name), None)


def _callee(call: ast.Call) -> str | None:
    f = call.func
    return f.id if isinstance(f, ast.Name) else f.attr if isinstance(f, ast.Attribute) else None


@cache
def _walked(scope: ast.AST) -> tuple[ast.AST, ...]:
    """ast.walk(scope), walked once (the scan asks again and again of the same functions)."""
    return tuple(ast.walk(scope))


def _assigned(scope: ast.AST, name: str, nested: bool = True) -> list[ast.expr]:
    """The values `name` is assigned in `scope` (`name = v`, and `a, name = x, v`)."""
    out = []
    for node in _walked(scope) if nested else getattr(scope, "body", []):
        if not isinstance(node, ast.Assign):
            continue
        for target in node.targets:
            if isinstance(target, ast.Name) and target.id == name:
                out.append(node.value)
            elif isinstance(target, ast.Tuple) and isinstance(node.value, ast.Tuple):
                pairs = zip(target.elts, node.value.elts, strict=False)
                out += [v for t, v in pairs if isinstance(t, ast.Name) and t.id == name]
    return out


@cache
def _calls(tree: ast.AST) -> tuple[ast.Call, ...]:
    return tuple(n for n in _walked(tree) if isinstance(n, ast.Call))


class Scanner:
    """Every rule id the modules under `root` emit (see the module docstring)."""

    def __init__(self, root: Path):
        self.modules = {m.name: m for m in map(_module, sorted(root.rglob("*.py")))}
        self.helpers: dict[tuple[str, str], tuple[Module, ast.FunctionDef]] = {
            (m.name, fn.name): (m, fn)
            for m in self.modules.values()
            for fn in ast.walk(m.tree)
            if isinstance(fn, ast.FunctionDef) and "rule" in _params(fn)
        }
        self.helper_severity: dict[tuple[str, str], frozenset[str]] = {}
        while self._helper_round():  # a helper's severities: those of the calls it passes `rule` to
            pass

    def _helper_round(self) -> bool:
        changed = False
        for key, (m, fn) in self.helpers.items():
            found = set(self.helper_severity.get(key, frozenset()))
            for call in _calls(fn):
                emitter = self.emitter(m, call)
                arg = self.rule_arg(call, emitter[1]) if emitter else None
                if emitter and isinstance(arg, ast.Name) and arg.id == "rule":
                    found |= emitter[0]
            if frozenset(found) != self.helper_severity.get(key, frozenset()):
                self.helper_severity[key], changed = frozenset(found), True
        return changed

    def emitter(self, m: Module, call: ast.Call) -> tuple[frozenset[str], tuple[str, str] | None] | None:
        """(severities, the rule-taking helper or None) of a call making a finding, else None."""
        name = _callee(call)
        if name is None:
            return None
        if isinstance(call.func, ast.Name):
            module, original = m.imports.get(name, ("", ""))
            if module == FINDINGS and original in SEVERITIES:
                return SEVERITIES[original], None
            if module == FINDINGS and original == "Finding":
                severity = ast.unparse(_argument(call, 1, "severity") or ast.Constant(""))
                return next((v for k, v in SEVERITIES.items() if severity.lower().endswith(k)), BOTH), None
            alias = self._alias(m, call, name)
            if alias is not None:
                return alias, None
            key = (module, original) if module else (m.name, name)
        else:
            key = (m.name, name)  # a method: only the module's own
        return (self.helper_severity.get(key, frozenset()), key) if key in self.helpers else None

    def _alias(self, m: Module, call: ast.Call, name: str) -> frozenset[str] | None:
        """`make = error if active else warning`: the severities `make` may have."""
        fn = m.enclosing(call)
        values = _assigned(fn, name) if fn is not None else []
        found = [self._severities(m, v) for v in values]
        return None if not found or any(f is None for f in found) else frozenset().union(*found)  # type: ignore[arg-type]

    def _severities(self, m: Module, node: ast.expr) -> frozenset[str] | None:
        if isinstance(node, ast.IfExp):
            a, b = self._severities(m, node.body), self._severities(m, node.orelse)
            return None if a is None or b is None else a | b
        module, original = m.imports.get(node.id, ("", "")) if isinstance(node, ast.Name) else ("", "")
        return SEVERITIES[original] if module == FINDINGS and original in SEVERITIES else None

    def rule_arg(self, call: ast.Call, helper: tuple[str, str] | None) -> ast.expr | None:
        if helper is None:
            return _argument(call, 0, "rule")
        fn = self.helpers[helper][1]
        args = [*fn.args.posonlyargs, *fn.args.args]
        defaults = dict(
            zip([a.arg for a in args[len(args) - len(fn.args.defaults) :]], fn.args.defaults, strict=True)
        )
        return _argument(call, _params(fn).index("rule"), "rule") or defaults.get("rule")

    def ids(self, m: Module, node: ast.expr, at: ast.AST) -> set[str] | None:
        """The ids `node` may be (empty for an id passed through or re-emitted); None: unknown."""
        if isinstance(node, ast.Constant) and isinstance(node.value, str):
            return {node.value}
        if isinstance(node, ast.IfExp):
            a, b = self.ids(m, node.body, at), self.ids(m, node.orelse, at)
            return None if a is None or b is None else a | b
        if isinstance(node, ast.Attribute) and node.attr == "rule":
            return set()
        if isinstance(node, ast.Name):
            return self._name(m, node.id, at)
        if isinstance(node, ast.JoinedStr):
            return self._fstring(m, node, at)
        return None

    def _union(self, m: Module, values: list[ast.expr]) -> set[str] | None:
        found = [self.ids(m, v, v) for v in values]
        return None if any(f is None for f in found) else set().union(*found)  # type: ignore[arg-type]

    def _name(self, m: Module, name: str, at: ast.AST) -> set[str] | None:
        fn = m.enclosing(at)
        if fn is not None and name == "rule" and name in _params(fn):
            return set()  # passed through: its callers' ids count
        local = _assigned(fn, name) if fn is not None else []
        if local:
            return self._union(m, local)
        constant = _assigned(m.tree, name, nested=False)
        if constant:
            return self._union(m, constant)
        module, original = m.imports.get(name, ("", ""))
        if module in self.modules:
            return self._name(self.modules[module], original, self.modules[module].tree)
        return None

    def _fstring(self, m: Module, node: ast.JoinedStr, at: ast.AST) -> set[str] | None:
        """`f"{family}.unreadable"` in a function taking `family` (what every caller passes), or
        `f"{_kind(param)}.missing"` with `_kind` a function of the module (what it returns)."""
        parts = node.values
        if len(parts) != 2 or not isinstance(parts[0], ast.FormattedValue):
            return None
        head, suffix = parts[0].value, parts[1]
        if not isinstance(suffix, ast.Constant):
            return None
        if isinstance(head, ast.Call) and isinstance(head.func, ast.Name):
            found = self._returns(m, head.func.id)
        elif isinstance(head, ast.Name):
            found = self._passed(m, head.id, m.enclosing(at))
        else:
            found = None
        return None if found is None else {f"{value}{suffix.value}" for value in found}

    def _returns(self, m: Module, name: str) -> set[str] | None:
        """What the module's function `name` returns (string literals and conditionals of them)."""
        fn = next((n for n in m.tree.body if isinstance(n, ast.FunctionDef) and n.name == name), None)
        values = [n.value for n in ast.walk(fn) if isinstance(n, ast.Return) and n.value] if fn else []
        return self._union(m, values) if values else None

    def _passed(self, m: Module, param: str, fn: ast.FunctionDef | None) -> set[str] | None:
        """Every value callers of `fn` pass for its parameter `param`."""
        if fn is None or param not in _params(fn):
            return None
        out: set[str] = set()
        for other in self.modules.values():
            for call in _calls(other.tree):
                imported = other.imports.get(fn.name, ("",))[0] == m.name
                if _callee(call) != fn.name or not (other is m or imported):
                    continue
                arg = _argument(call, _params(fn).index(param), param)
                found = self.ids(other, arg, call) if arg is not None else None
                if found is None:
                    return None
                out |= found
        return out

    def scan(self) -> Scan:
        result = Scan()
        for m in self.modules.values():
            for call in _calls(m.tree):
                emitter = self.emitter(m, call)
                if emitter is None:
                    continue
                arg = self.rule_arg(call, emitter[1])
                found = self.ids(m, arg, call) if arg is not None else None
                if found is None:
                    result.unresolved.append(f"{m.where(call)}: {ast.unparse(call)[:100]}")
                for rule_id in found or ():
                    result.emitted.setdefault(rule_id, set()).update(emitter[0])
                    result.sites.setdefault(rule_id, m.where(call))
        return result


BOTH = frozenset({"error", "warning"})


@cache
def scanned() -> Scan:
    return Scanner(PACKAGE).scan()


SCAN = pytest.mark.xdist_group("rule_scan")  # one worker scans (`--dist loadgroup`), once


# -- the registry against the scan --------------------------------------------------------------


@SCAN
def test_scan_reads_every_rule_id():
    assert scanned().unresolved == [], "rule ids the scan cannot read (teach it the new pattern)"
    assert len(scanned().emitted) > 100  # the scan still finds the rules at all


@SCAN
def test_every_emitted_rule_is_registered():
    known = {r.id for r in all_rules()}
    missing = {i: scanned().sites[i] for i in sorted(set(scanned().emitted) - known)}
    assert not missing, f"add these to marm_setup/validate/registry/rules.yaml: {missing}"


@SCAN
def test_no_stale_entries():
    stale = sorted({r.id for r in all_rules()} - set(scanned().emitted))
    assert not stale, f"no longer emitted anywhere in marm_setup/, remove from rules.yaml: {stale}"


@SCAN
def test_emitted_severities_are_registered():
    known = {r.id for r in all_rules()}  # unregistered ones: test_every_emitted_rule_is_registered
    wrong = {
        i: (sorted(found), severity_of(i))
        for i, found in sorted(scanned().emitted.items())
        if i in known and not all(allows(i, s) for s in found)
    }
    assert not wrong, f"emitted with a severity rules.yaml does not give it: {wrong}"


def test_every_entry_says_what_moveit_does_and_where():
    for r in all_rules():
        assert r.moveit_does.strip() and r.source.strip(), r.id
        assert (len(r.severities) > 1) == bool(r.why), f"{r.id}: a why exactly when it has two severities"
        assert rule_family(r.family).description


def test_every_family_has_rules():
    used = {r.family for r in all_rules()}
    assert sorted(f.name for f in rule_families() if f.name not in used) == []


def test_lookups():
    assert rule("srdf.unknown-link").family == "srdf"
    assert severity_of("controller.none") == "warning"
    assert severity_of("srdf.virtual-joint-child") == "error|warning"
    assert allows("srdf.unknown-link", "warning") and not allows("matrix.stale", "error")
    assert not allows("no.such-rule", "error")
    with pytest.raises(KeyError, match="did you mean 'srdf.unknown-link'"):
        rule("srdf.unknown-lnk")
    with pytest.raises(KeyError, match="no rule family 'srd'"):
        rule_family("srd")


# -- docs/rules.md and the command ----------------------------------------------------------------


def test_docs_rules_md_is_current():
    written = DOC.read_text(encoding="utf-8") if DOC.exists() else ""
    now = rules_markdown()
    diff = "".join(
        difflib.unified_diff(written.splitlines(True), now.splitlines(True), "docs/rules.md", "now")
    )
    assert written == now, f"regenerate: marm-setup rules --format markdown > docs/rules.md\n{diff[:3000]}"
    for r in all_rules():
        assert f"`{r.id}`" in written


def test_rules_command_formats():
    runner = CliRunner()
    text = runner.invoke(app, ["rules"])
    assert text.exit_code == 0 and "controller.none" in text.output and "WHAT MOVEIT DOES" in text.output
    as_json = runner.invoke(app, ["rules", "--format", "json"])
    import json

    doc = json.loads(as_json.output)
    assert {r["id"] for r in doc["rules"]} == {r.id for r in all_rules()}
    markdown = runner.invoke(app, ["rules", "--format", "markdown"])
    assert markdown.output == rules_markdown()


# -- at run time ------------------------------------------------------------------------------------


def test_findings_of_a_validation_keep_to_the_registry(ros2_packages, tmp_path):
    """A validation of a generated package, broken in a few places, emits only registered
    rules with a severity the registry allows."""
    import shutil

    from marm_setup.validate import validate

    generated = ros2_packages.get("marm", "humble")
    assert generated.exit_code == 0, generated.output
    pkg = tmp_path / generated.out.name
    shutil.copytree(generated.out, pkg)
    srdf = next((pkg / "config").glob("*.srdf"))
    text = srdf.read_text(encoding="utf-8")
    ghost = '<group name="ghost"><link name="nowhere"/></group>'
    pair = '<disable_collisions link1="nowhere" link2="base_link" reason="Never"/>'
    srdf.write_text(text.replace("</robot>", f"{ghost}{pair}</robot>"), encoding="utf-8")
    findings = validate(pkg, package_paths=generated.roots, plan=False, matrix_trials=50).findings
    # srdf.unknown-link both ways: an error in the group, a warning in the pair srdfdom drops
    assert {("srdf.unknown-link", "error"), ("srdf.unknown-link", "warning")} <= {
        (f.rule, str(f.severity)) for f in findings
    }
    wrong = [(f.rule, str(f.severity)) for f in findings if not allows(f.rule, f.severity)]
    assert wrong == []
