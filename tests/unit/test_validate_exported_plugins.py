"""Plugin classes exported by a package on the package paths. pluginlib finds a class by its
lookup name in the plugin description files that packages export for the base class's package
(`<export><moveit_core plugin="${prefix}/x.xml"/></export>`; pluginlib class_loader_imp.hpp
getPluginXmlPaths / processXMLFile): the name's prefix need not be a package
(moveit_pr2's pr2_moveit_plugins exports `pr2_moveit_controller_manager/Pr2MoveItControllerManager`
and `pr2_arm_kinematics/PR2ArmKinematicsPlugin`). A class such a package exports loads."""

from __future__ import annotations

from marm_setup.findings import Finding
from tests.validate_helpers import Good, generate_marm, replace_text, run

MANAGER = "acme_controller_manager/AcmeControllerManager"
SOLVER = "acme_arm_kinematics/AcmeArmKinematicsPlugin"
PLUGINS_XML = f"""<library path="libacme_moveit_plugins">
  <class name="{MANAGER}" type="acme::ControllerManager" base_class_type="moveit_controller_manager::MoveItControllerManager"/>
  <class name="{SOLVER}" type="acme::Kinematics" base_class_type="kinematics::KinematicsBase"/>
</library>
"""
PACKAGE_XML = """<package format="2"><name>acme_moveit_plugins</name><version>1.0.0</version>
<description>plugins</description><maintainer email="a@b.c">A</maintainer><license>BSD</license>
<buildtool_depend>catkin</buildtool_depend>
<export><moveit_core plugin="${prefix}/acme_plugins.xml"/></export></package>
"""


def plugin_findings(found: list[Finding]) -> list[tuple[str, str]]:
    return sorted(
        (f.rule, str(f.severity)) for f in found if f.rule in ("params.plugin", "kinematics.unknown-solver")
    )


def test_classes_a_held_package_exports_are_loadable(tmp_path):
    pkg = generate_marm(tmp_path, "ros1")
    replace_text(
        pkg,
        "launch/simple_moveit_controller_manager.launch.xml",
        "moveit_simple_controller_manager/MoveItSimpleControllerManager",
        MANAGER,
    )
    replace_text(pkg, "config/kinematics.yaml", "kdl_kinematics_plugin/KDLKinematicsPlugin", SOLVER)
    plugins = tmp_path / "plugins" / "acme_moveit_plugins"
    plugins.mkdir(parents=True)
    held = Good(pkg, (tmp_path / "plugins",))
    assert plugin_findings(run(pkg, held, matrix_trials=0)) == [
        ("kinematics.unknown-solver", "warning"),
        ("params.plugin", "error"),
    ]
    (plugins / "package.xml").write_text(PACKAGE_XML)
    (plugins / "acme_plugins.xml").write_text(PLUGINS_XML)
    assert plugin_findings(run(pkg, held, matrix_trials=0)) == []
    (plugins / "acme_plugins.xml").write_text(PLUGINS_XML.replace(SOLVER, "acme_arm_kinematics/Other"))
    assert plugin_findings(run(pkg, held, matrix_trials=0)) == [("kinematics.unknown-solver", "warning")]
