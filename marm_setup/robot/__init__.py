"""The robot: URDF/xacro loading, ROS package lookup, meshes, the frozen RobotModel, batched forward kinematics, and its text description."""
