"""The setup model (`marm_setup.yaml`): dataclasses, YAML I/O, inference from a robot, group queries, SRDF reading and the setup checks."""
