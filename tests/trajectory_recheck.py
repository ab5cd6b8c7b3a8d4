"""An independent re-check of a written trajectory with pinocchio + coal (the `pin` wheel).

Nothing here uses marm_setup's planner, timing, FK or collision code: the YAML is read with
pyyaml, the motion between points is rebuilt (constant acceleration, as the fake controller
assumes), the robot comes from the URDF text through pinocchio, the SRDF's disabled pairs are
removed by pinocchio, and every state at a joint step finer than the planner's is checked.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import yaml


def pinocchio_models(urdf_xml: str, meshes: dict[str, str], srdf: Path, work: Path):
    """(model, collision model with the SRDF's pairs removed); `meshes` maps URIs to files."""
    import pinocchio as pin

    for uri, path in meshes.items():
        urdf_xml = urdf_xml.replace(f'"{uri}"', f'"{path}"')
    urdf = work / "robot.urdf"
    urdf.write_text(urdf_xml, encoding="utf-8")
    model = pin.buildModelFromUrdf(str(urdf))
    geom = pin.buildGeomFromUrdf(model, str(urdf), pin.GeometryType.COLLISION)
    geom.addAllCollisionPairs()
    pin.removeCollisionPairs(model, geom, str(srdf))
    pin.loadReferenceConfigurations(model, str(srdf))
    return model, geom


def states(doc: dict, max_step: float) -> tuple[np.ndarray, np.ndarray, np.ndarray, float]:
    """(positions, velocities, accelerations) along the motion, no two states `max_step` apart,
    and the largest gap between where the motion arrives and where the next point says."""
    t = np.array([p["time_from_start"] for p in doc["points"]], dtype=float)
    pos = np.array([p["positions"] for p in doc["points"]], dtype=float)
    vel = np.array([p["velocities"] for p in doc["points"]], dtype=float)
    out_q, out_v, out_a = [pos[:1]], [vel[:1]], [np.zeros((1, pos.shape[1]))]
    gap = 0.0
    for k in range(len(t) - 1):
        dt = t[k + 1] - t[k]
        acc = (vel[k + 1] - vel[k]) / dt
        speed = max(np.linalg.norm(vel[k]), np.linalg.norm(vel[k + 1]))
        n = int(np.ceil(speed * dt / max_step)) + 1
        tau = dt * np.arange(1, n + 1)[:, None] / n
        out_q.append(pos[k] + vel[k] * tau + 0.5 * acc * tau**2)
        out_v.append(vel[k] + acc * tau)
        out_a.append(np.broadcast_to(acc, tau.shape[:1] + acc.shape))
        gap = max(gap, float(np.abs(out_q[-1][-1] - pos[k + 1]).max()))
    return np.concatenate(out_q), np.concatenate(out_v), np.concatenate(out_a), gap


def recheck(path: Path, model, geom, q_base: np.ndarray, max_step: float) -> dict:
    """Check a trajectory file; returns what was found (for asserts with messages)."""
    import pinocchio as pin

    doc = yaml.safe_load(path.read_text(encoding="utf-8"))
    idx = [model.joints[model.getJointId(name)].idx_q for name in doc["joint_names"]]
    q_traj, v_traj, a_traj, gap = states(doc, max_step)
    data, gdata = model.createData(), pin.GeometryData(geom)
    colliding = []
    for row in q_traj:
        q = q_base.copy()
        q[idx] = row
        if pin.computeCollisions(model, data, geom, gdata, q, False):
            for k, result in enumerate(gdata.collisionResults):
                if result.isCollision():
                    pair = geom.collisionPairs[k]
                    colliding.append(
                        (geom.geometryObjects[pair.first].name, geom.geometryObjects[pair.second].name)
                    )
    steps = np.linalg.norm(np.diff(q_traj, axis=0), axis=1)
    return {
        "joint_names": doc["joint_names"],
        "states": len(q_traj),
        "inconsistency": gap,
        "max_step": float(steps.max()),
        "colliding": colliding,
        "start": q_traj[0],
        "end": q_traj[-1],
        "below_lower": bool(np.any(q_traj < model.lowerPositionLimit[idx] - 1e-9)),
        "above_upper": bool(np.any(q_traj > model.upperPositionLimit[idx] + 1e-9)),
        "max_velocity": np.abs(v_traj).max(axis=0),
        "max_acceleration": np.abs(a_traj).max(axis=0),
        "velocity_limit": model.velocityLimit[
            [model.joints[model.getJointId(n)].idx_v for n in doc["joint_names"]]
        ],
    }
