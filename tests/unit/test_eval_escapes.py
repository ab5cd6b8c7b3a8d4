"""`$(eval ...)` and substitutions on hostile input (issue 23, "Code execution and escapes"):
the restricted evaluator refuses what is not an arg lookup, literal, arithmetic, comparison or
conditional, bounds the work, runs in the bounded child, never re-reads what a substitution
gave, and under `--untrusted` evaluates nothing."""

from __future__ import annotations

import pytest

from marm_setup.package.substitution import Scope, SubstitutionError, substitute
from marm_setup.untrusted import no_package_code

# The audit's reproducer: NFKC look-alike underscores pass a `'__' in text` guard, and Python
# normalises them to `__` (os._wrap_close's globals hold os.system).
LOOKALIKE = "\uff3f"
ESCAPE = (
    "[c for c in ()._{u}class_{u}._{u}base_{u}._{u}subclasses_{u}() if c._{u}name_{u} == '_wrap_close']"
    "[0]._{u}init_{u}._{u}globals_{u}['system']('touch {marker}')"
)


def test_nfkc_lookalike_escape_runs_nothing(tmp_path):
    marker = tmp_path / "ran"
    expression = ESCAPE.format(u=LOOKALIKE, marker=marker)
    with pytest.raises(SubstitutionError, match="not evaluated"):
        substitute(f"$(eval {expression})", Scope())
    assert not marker.exists()


@pytest.mark.parametrize(
    "expression",
    [
        "9**9**9",  # the audit's: a big-integer power runs in C, beyond any signal
        "'a' * 10**9",
        "[0] * 10**9",
        "'%*d' % (10**9, 1)",
        "10**5000",
    ],
)
def test_unbounded_work_is_refused_at_once(expression):
    with pytest.raises(SubstitutionError, match="larger than|longer than|not evaluated"):
        substitute(f"$(eval {expression})", Scope())


@pytest.mark.parametrize(
    "expression, what",
    [
        ("().__class__", "attribute"),
        ("(lambda: 1)()", "Lambda"),
        ("[x for x in 'ab']", "ListComp"),
        ("open('/etc/passwd')", "call open"),
        ("__import__('os')", "call __import__"),
        ("x := 1", "not a Python expression"),
    ],
)
def test_anything_but_the_allow_list_is_one_clear_refusal(expression, what):
    with pytest.raises(SubstitutionError, match=what):
        substitute(f"$(eval {expression})", Scope({"x": "1"}))


@pytest.mark.parametrize(
    "expression, args, value",
    [
        ("arg('pipeline') not in ['ompl', 'pilz_industrial_motion_planner']", {"pipeline": "chomp"}, "True"),
        ("rviz_config == ''", {"rviz_config": ""}, "True"),
        ("arg('moveit_controller_manager') == 'fake'", {"moveit_controller_manager": "fake"}, "True"),
        ("not arg('a') and arg('b')", {"a": "false", "b": "true"}, "True"),
        ("'x' if arg('n') > 2 else 'y'", {"n": "3"}, "x"),
        ("2 * pi * radius", {"radius": "0.5"}, str(2 * 3.141592653589793 * 0.5)),
        ("radians(180) == pi", {}, "True"),
        ("optenv('MARM_SETUP_NO_SUCH_VARIABLE', 'dflt') + '_' + str(int('7') // 2)", {}, "dflt_3"),
        ("{'sim': 'a.yaml', 'real': 'b.yaml'}[arg('mode')]", {"mode": "real"}, "b.yaml"),
        ("'robot'[1:3]", {}, "ob"),
        ("2**10", {}, "1024"),
    ],
)
def test_what_moveit_packages_write_evaluates_as_roslaunch_does(expression, args, value):
    assert substitute(f"$(eval {expression})", Scope(args)) == value


def test_ros2_eval_takes_the_substitutions_inside_it():
    scope = Scope({"radius": "1.5"}, ros2=True)
    assert substitute("r=$(eval 2.0 * $(var radius))", scope) == "r=3.0"


def test_a_substitutions_result_is_never_substituted_again(tmp_path):
    """roslaunch resolves the text as written; a folder named `$(eval ...)` is only a name."""
    folder = tmp_path / "$(eval 6 * 7)" / "$(arg secret)"
    scope = Scope({"secret": "s3cret"}, dirname=str(folder))
    assert substitute("$(dirname)/config.yaml", scope) == f"{folder}/config.yaml"
    assert substitute("$(arg a)", Scope({"a": "$(arg secret)", "secret": "x"})) == "$(arg secret)"


def test_untrusted_evaluates_nothing_and_says_so():
    with no_package_code() as skipped, pytest.raises(SubstitutionError, match="--untrusted"):
        substitute("$(eval 1 + 1)", Scope())
    assert skipped == ["$(eval 1 + 1)"]
    assert substitute("$(arg a)", Scope({"a": "b"})) == "b"  # plain substitutions still resolve


def test_the_expression_is_quoted_short_and_printable():
    long = "'" + "\x1b[31m" * 200 + "'.x"
    with pytest.raises(SubstitutionError) as caught:
        substitute(f"$(eval {long})", Scope())
    assert "\x1b" not in str(caught.value) and len(str(caught.value)) < 300


def test_an_expression_over_the_same_args_is_evaluated_once(tmp_path):
    """The same `$(eval)` over the same args (an include read twice) is one child process, not
    one each; another arg value is evaluated again."""
    from marm_setup.package import substitution

    substitution._MEMO.clear()
    scope = Scope({"n": "2"}, dirname=str(tmp_path))
    assert [substitute("$(eval n * 21)", scope) for _ in range(3)] == ["42"] * 3
    assert len(substitution._MEMO) == 1
    assert substitute("$(eval n * 21)", Scope({"n": "1"}, dirname=str(tmp_path))) == "21"
    assert len(substitution._MEMO) == 2
