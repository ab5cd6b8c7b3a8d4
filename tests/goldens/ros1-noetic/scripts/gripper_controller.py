#!/usr/bin/env python3
"""A control_msgs/GripperCommand action server for an ArbotiX gripper servo (Python 3, Noetic).

arbotix_controllers' gripper_controller is Python 2 (`import thread`) and does not start on
Noetic; this serves the same `<node>/gripper_action` and drives the servo the same way: it
publishes the commanded position, mapped to a servo angle, to the ArbotiX driver's
`<joint>/command` (std_msgs/Float64, radians) and reports the joint's position.

Parameters (private): joint, center, scale (angle = center + scale * position), min_opening,
max_opening (the command is clamped to them), timeout [s].
"""

import actionlib
import rospy
from control_msgs.msg import GripperCommandAction, GripperCommandFeedback, GripperCommandResult
from sensor_msgs.msg import JointState
from std_msgs.msg import Float64


class GripperActionServer:
    def __init__(self):
        self.joint = rospy.get_param("~joint")
        self.center = float(rospy.get_param("~center", 0.0))
        self.scale = float(rospy.get_param("~scale", 1.0))
        self.lower = float(rospy.get_param("~min_opening", -1.0e9))
        self.upper = float(rospy.get_param("~max_opening", 1.0e9))
        self.timeout = float(rospy.get_param("~timeout", 5.0))
        self.position = None
        self.command = rospy.Publisher(self.joint + "/command", Float64, queue_size=1)
        rospy.Subscriber("joint_states", JointState, self.on_joint_states)
        self.server = actionlib.SimpleActionServer(
            "~gripper_action", GripperCommandAction, execute_cb=self.execute, auto_start=False
        )
        self.server.start()
        rospy.loginfo("%s: GripperCommand for %s", rospy.get_name(), self.joint)

    def on_joint_states(self, msg):
        if self.joint in msg.name:
            self.position = msg.position[msg.name.index(self.joint)]

    def execute(self, goal):
        target = min(max(goal.command.position, self.lower), self.upper)
        self.command.publish(Float64(self.center + self.scale * target))
        deadline = rospy.Time.now() + rospy.Duration(self.timeout)
        rate = rospy.Rate(20)
        while not rospy.is_shutdown() and rospy.Time.now() < deadline:
            if self.server.is_preempt_requested():
                self.server.set_preempted()
                return
            feedback = GripperCommandFeedback(position=self.position or 0.0)
            self.server.publish_feedback(feedback)
            if self.position is not None and abs(self.position - target) < 1.0e-3:
                break
            rate.sleep()
        reached = self.position is not None and abs(self.position - target) < 1.0e-3
        result = GripperCommandResult(
            position=self.position or 0.0, reached_goal=reached, stalled=not reached
        )
        self.server.set_succeeded(result)


if __name__ == "__main__":
    rospy.init_node("gripper_controller")
    GripperActionServer()
    rospy.spin()
