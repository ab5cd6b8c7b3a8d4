"""The ROS 2 consumer harness's scripts run in forks of one interpreter that has already imported
launch, launch_ros and rclpy: each run is still its own process (its environment, argv, file
descriptors and every change it makes to the modules die with it) but skips their import (about
0.45 s of CPU a run, over a hundred runs a session). One such interpreter per harness python per
test process; `run` stands in for `subprocess.run([python, *argv], ...)`.
"""

from __future__ import annotations

import atexit
import json
import os
import select
import subprocess
import tempfile
from pathlib import Path

# The zygote: imports what the harness imports, then for each request line (JSON: argv, env, out,
# err) forks a child that runs argv as `python *argv` would (a script path, or -c CODE), with its
# stdout and stderr in the files named, and answers with the child's exit status.
_ZYGOTE = """
import json, os, runpy, sys
sys.path.insert(0, {harness!r})
import check_ros2_pkg, launch, launch.actions, launch_ros, launch_xml, launch_yaml, rclpy, yaml
from launch.launch_description_sources import AnyLaunchDescriptionSource
del check_ros2_pkg
requests, answers = sys.stdin, os.fdopen(os.dup(1), "w")
for line in requests:
    request = json.loads(line)
    pid = os.fork()
    if pid == 0:
        code = 1
        try:
            for fd, path in ((1, request["out"]), (2, request["err"])):
                os.dup2(os.open(path, os.O_WRONLY | os.O_CREAT | os.O_TRUNC, 0o600), fd)
            os.environ.clear()
            os.environ.update(request["env"])
            argv = request["argv"]
            if argv[0] == "-c":
                sys.argv = argv[1:]
                sys.argv[0] = "-c"
                exec(compile(argv[1], "<string>", "exec"), {{"__name__": "__main__"}})
            else:
                sys.argv = argv
                sys.path[0] = os.path.dirname(os.path.abspath(argv[0]))
                runpy.run_path(argv[0], run_name="__main__")
            code = 0
        except SystemExit as stop:
            code = stop.code if isinstance(stop.code, int) else (0 if stop.code is None else 1)
        except BaseException:
            import traceback
            traceback.print_exc()
        finally:
            import atexit
            atexit._run_exitfuncs()
            sys.stdout.flush()
            sys.stderr.flush()
            os._exit(code)
    _, status = os.waitpid(pid, 0)
    answers.write(json.dumps({{"returncode": os.waitstatus_to_exitcode(status)}}) + "\\n")
    answers.flush()
"""
_ZYGOTES: dict[str, subprocess.Popen] = {}


def run(
    python: Path, argv: list[str], env: dict[str, str], timeout: float
) -> subprocess.CompletedProcess[str]:
    """`subprocess.run([python, *argv], env=env, capture_output=True, text=True, timeout=timeout)`,
    run in a fork of `python`'s zygote."""
    zygote = _zygote(str(python))
    with tempfile.TemporaryDirectory(prefix="ros2_zygote_") as folder:
        out, err = os.path.join(folder, "out"), os.path.join(folder, "err")
        request = {"argv": [str(a) for a in argv], "env": env, "out": out, "err": err}
        assert zygote.stdin is not None and zygote.stdout is not None
        zygote.stdin.write(json.dumps(request) + "\n")
        zygote.stdin.flush()
        ready, _, _ = select.select([zygote.stdout], [], [], timeout)
        if not ready:
            _stop(str(python))
            raise subprocess.TimeoutExpired([str(python), *argv], timeout)
        answer = zygote.stdout.readline()
        if not answer:
            _stop(str(python))
            raise RuntimeError(
                f"the zygote of {python} died: {Path(err).read_text(errors='replace')[-2000:]}"
            )
        code = json.loads(answer)["returncode"]
        stdout = Path(out).read_text(encoding="utf-8", errors="replace")
        stderr = Path(err).read_text(encoding="utf-8", errors="replace")
    return subprocess.CompletedProcess([str(python), *argv], code, stdout, stderr)


def _zygote(python: str) -> subprocess.Popen:
    from tests.ros2_harness import HARNESS  # which imports this module

    if python not in _ZYGOTES or _ZYGOTES[python].poll() is not None:
        _ZYGOTES[python] = subprocess.Popen(
            [python, "-c", _ZYGOTE.format(harness=str(HARNESS))],
            stdin=subprocess.PIPE,
            stdout=subprocess.PIPE,
            stderr=subprocess.DEVNULL,
            text=True,
            start_new_session=True,
        )
    return _ZYGOTES[python]


def _stop(python: str) -> None:
    zygote = _ZYGOTES.pop(python, None)
    if zygote is not None and zygote.poll() is None:
        os.killpg(zygote.pid, 9)
        zygote.wait()


@atexit.register
def _stop_all() -> None:
    for python in list(_ZYGOTES):
        _stop(python)
