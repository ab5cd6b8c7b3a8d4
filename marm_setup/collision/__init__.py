"""Self-collision: link pairs and reasons, the coal collision scene, the MoveIt collision matrix, SRDF updates and the matrix report."""
