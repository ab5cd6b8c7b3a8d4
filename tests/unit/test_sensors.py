"""3D perception in the setup: MoveIt's per-type defaults, the checks of the `sensors` key, and
the files it renders for each target (nothing without the key)."""

from __future__ import annotations

import dataclasses

import pytest
import yaml
from lxml import etree

from marm_setup.moveit_params.vocabulary import SENSOR_TYPES
from marm_setup.setup.checks import check_setup
from marm_setup.setup.model import Sensor
from marm_setup.setup.sensors import plan_sensor
from marm_setup.setup.yaml_io import setup_from_dict, setup_to_dict
from tests.render_helpers import assert_check_error, assert_yaml_errors, marm_with, rendered_files

CAMERA = Sensor("wrist_camera", "pointcloud", "/wrist_camera/depth/points")
DEPTH = Sensor(
    "head_camera", "depth_image", "/head_camera/depth/image_raw", far_clipping_plane_distance=3.0, ns="head"
)


def test_moveits_defaults_per_type_and_given_values():
    assert dict(plan_sensor(CAMERA).parameters) == {
        "point_cloud_topic": "/wrist_camera/depth/points",
        "max_range": 5.0,
        "padding_offset": 0.1,
        "padding_scale": 1.0,
        "point_subsample": 1,
        "max_update_rate": 1.0,
        "filtered_cloud_topic": "filtered_cloud",
    }
    depth = plan_sensor(DEPTH)
    assert depth.plugin == "occupancy_map_monitor/DepthImageOctomapUpdater"
    values = dict(depth.parameters)
    assert values["image_topic"] == DEPTH.topic and values["far_clipping_plane_distance"] == 3.0
    assert values["ns"] == "head" and values["skip_horizontal_pixels"] == 6
    assert list(values)[:-1] == ["image_topic", *(k for k, _ in SENSOR_TYPES["depth_image"].defaults)]


@pytest.mark.parametrize(("target", "distro"), [("ros1", "noetic"), ("ros2", "humble"), ("ros2", "jazzy")])
def test_nothing_without_the_key(target, distro):
    files = rendered_files(*marm_with(target, distro))
    assert not [p for p in files if "sensor" in p]
    text = "\n".join(files.values())
    assert "octomap" not in text and "moveit_ros_perception" not in text


def test_ros1_setup_assistant_layout():
    model, robot = marm_with("ros1", sensors=(CAMERA, DEPTH), octomap_resolution=0.05)
    check_setup(model, robot)
    files = rendered_files(model, robot)
    sensors = yaml.safe_load(files["config/sensors_3d.yaml"])["sensors"]
    assert [s["sensor_plugin"] for s in sensors] == [
        SENSOR_TYPES["pointcloud"].plugin,
        SENSOR_TYPES["depth_image"].plugin,
    ]
    assert sensors[0]["point_cloud_topic"] == CAMERA.topic and isinstance(sensors[0]["point_subsample"], int)
    manager = etree.fromstring(files["launch/sensor_manager.launch.xml"].encode())
    params = {p.get("name"): p.get("value") for p in manager.iter("param")}
    assert params == {"octomap_frame": "world", "octomap_resolution": "0.05"}
    assert manager.find("rosparam").get("file") == "$(find marm_moveit_config)/config/sensors_3d.yaml"
    include = manager.find("include").get("file")
    assert include.endswith("/launch/$(arg moveit_sensor_manager)_moveit_sensor_manager.launch.xml")
    etree.fromstring(files["launch/marm_moveit_sensor_manager.launch.xml"].encode())
    move_group = etree.fromstring(files["launch/move_group.launch"].encode())
    (sensor_include,) = [i for i in move_group.iter("include") if "sensor_manager" in i.get("file")]
    assert sensor_include.get("ns") == "move_group"
    assert "<exec_depend>moveit_ros_perception</exec_depend>" in files["package.xml"]


@pytest.mark.parametrize("distro", ["humble", "jazzy"])
def test_ros2_sensors_are_move_groups_alone(distro):
    model, robot = marm_with("ros2", distro, sensors=(CAMERA, DEPTH), octomap_frame="base_link")
    check_setup(model, robot)
    files = rendered_files(model, robot)
    params = yaml.safe_load(files["config/sensors_3d.yaml"])["/**"]["ros__parameters"]
    assert params["sensors"] == ["wrist_camera", "head_camera"]
    assert params["octomap_frame"] == "base_link" and params["octomap_resolution"] == 0.025
    camera = params["wrist_camera"]
    assert camera["sensor_plugin"] == SENSOR_TYPES["pointcloud"].plugin
    assert isinstance(camera["max_range"], float) and isinstance(camera["point_subsample"], int)
    assert isinstance(params["head_camera"]["queue_size"], int) and params["head_camera"]["ns"] == "head"
    loaders = {
        path: [p.get("from") for p in etree.fromstring(text.encode()).iter("param") if p.get("from")]
        for path, text in files.items()
        if path.endswith(".launch.xml")
    }
    users = [
        path for path, froms in loaders.items() if any(f.endswith("/config/sensors_3d.yaml") for f in froms)
    ]
    assert users == ["launch/move_group.launch.xml"]  # not rviz2, not servo (Humble's would start an octomap)


def test_sensors_round_trip_with_only_what_was_given():
    model, _ = marm_with("ros2", sensors=(CAMERA, DEPTH), octomap_resolution=0.05)
    data = setup_to_dict(model)
    assert data["sensors"][0] == {"name": "wrist_camera", "type": "pointcloud", "topic": CAMERA.topic}
    assert setup_from_dict(data) == model


BAD = {
    "depth key on a point cloud": (
        {"sensors": (dataclasses.replace(CAMERA, queue_size=3),)},
        "sensors[wrist_camera].queue_size",
        "a pointcloud sensor has no 'queue_size'",
    ),
    "point cloud key on a depth image": (
        {"sensors": (dataclasses.replace(DEPTH, max_range=3.0),)},
        "sensors[head_camera].max_range",
        "a depth_image sensor has no 'max_range'",
    ),
    "duplicate": ({"sensors": (CAMERA, CAMERA)}, "sensors[wrist_camera]", "duplicate sensor name"),
    "move_group namespace": (
        {"sensors": (dataclasses.replace(CAMERA, name="ompl"),)},
        "sensors[ompl]",
        "move_group's own parameter namespaces",
    ),
    "bad name": (
        {"sensors": (dataclasses.replace(CAMERA, name="wrist-camera"),)},
        "sensors[wrist-camera]",
        "not a valid sensor name",
    ),
    "empty topic": (
        {"sensors": (dataclasses.replace(CAMERA, topic=""),)},
        "sensors[wrist_camera].topic",
        "empty topic",
    ),
    "topic with a space": (
        {"sensors": (dataclasses.replace(CAMERA, topic="/wrist camera/points"),)},
        "sensors[wrist_camera].topic",
        "not a valid topic name",
    ),
    "negative padding": (
        {"sensors": (dataclasses.replace(CAMERA, padding_offset=-0.1),)},
        "sensors[wrist_camera].padding_offset",
        "must be >= 0",
    ),
    "no subsampling step": (
        {"sensors": (dataclasses.replace(CAMERA, point_subsample=0),)},
        "sensors[wrist_camera].point_subsample",
        "must be > 0",
    ),
    "near after far": (
        {"sensors": (dataclasses.replace(DEPTH, near_clipping_plane_distance=4.0),)},
        "sensors[head_camera].near_clipping_plane_distance",
        "must be before the far one",
    ),
    "resolution": ({"sensors": (CAMERA,), "octomap_resolution": 0.0}, "octomap_resolution", "must be > 0"),
}


@pytest.mark.parametrize("case", list(BAD))
def test_bad_sensors_name_the_key(case):
    changes, element, message = BAD[case]
    assert_check_error(*marm_with("ros2", "humble", **changes), element, message)


def test_yaml_errors_in_the_sensors_key_name_the_path():
    model, _ = marm_with("ros2", "humble")
    cases = [
        (
            {"sensors": [{"name": "c", "type": "point_cloud", "topic": "/p"}]},
            "sensors[c].type",
            "did you mean 'pointcloud'?",
        ),
        (
            {"sensors": [{"name": "c", "type": "pointcloud", "topic": "/p", "max_rang": 1.0}]},
            "sensors[c].max_rang",
            "'max_range'",
        ),
        ({"sensors": [{"name": "c", "type": "pointcloud"}]}, "sensors[c]", "missing key 'topic'"),
        (
            {"sensors": [{"name": "c", "type": "pointcloud", "topic": "/p", "point_subsample": 1.5}]},
            "sensors[c].point_subsample",
            "expected an integer",
        ),
        ({"octomap_resolutoin": 0.1}, "octomap_resolutoin", "did you mean 'octomap_resolution'"),
    ]
    assert_yaml_errors(model, cases)
