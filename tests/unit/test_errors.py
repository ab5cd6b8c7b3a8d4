"""The error root: one class per kind, the exit code from the type, the one-line format."""

from __future__ import annotations

import pytest

from marm_setup.errors import (
    ConflictError,
    InputError,
    MarmError,
    MeshNotFound,
    PackageNotFound,
    PlanningFailed,
)
from marm_setup.robot.ros_packages import resolve_uri


@pytest.mark.parametrize(
    "error, code",
    [
        (InputError("x"), 2),
        (MeshNotFound("x", uri="m.stl"), 2),
        (PackageNotFound("x", package="p"), 2),
        (ConflictError("x"), 2),
        (PlanningFailed("x"), 1),
    ],
)
def test_exit_code_comes_from_the_type(error, code):
    assert isinstance(error, MarmError) and error.exit_code == code


def test_message_names_file_and_element():
    assert (
        str(MeshNotFound("not found", uri="a.stl", path="r.urdf", element="link[a]"))
        == "r.urdf: link[a]: not found"
    )


def test_resolving_a_mesh_raises_the_kind_of_failure(tmp_path):
    with pytest.raises(PackageNotFound) as raised:
        resolve_uri("package://nopkg/m.stl", tmp_path, {}, path="r.urdf", element="link[a]")
    assert raised.value.package == "nopkg"
    with pytest.raises(MeshNotFound) as missing:
        resolve_uri("package://pkg/m.stl", tmp_path, {"pkg": tmp_path}, path="r.urdf", element="link[a]")
    assert missing.value.uri == "package://pkg/m.stl"
