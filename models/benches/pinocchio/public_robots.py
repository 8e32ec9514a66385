"""Robots from example-robot-data for the comparison with Pinocchio (run by public.sh).

    python public_robots.py OUT_DIR NAME...

For each robot NAME of ROBOTS it writes, into OUT_DIR:
  - NAME.urdf: the package's URDF with joint damping and friction removed (Pinocchio's
    rnea ignores them, the generated inverse dynamics would add damping q̇), nothing else
    changed;
  - NAME.json: the model as Pinocchio builds it from that file (free-flyer root for the
    legged robots), in the layout of tests/data/pinocchio/*.json that build/timing reads
    (joints in Pinocchio's depth-first order, each with its parent, axis and placement;
    bodies with the inertia Pinocchio merged into each joint), and 20 seeded states with
    Pinocchio's outputs at them: rnea, crba, aba, nle, gravity, C v and the energies
    (timing checks its own model against them), the derivatives of rnea and aba and M⁻¹,
    dA_g v, and the kinematics the generated code is checked against before it is timed (oMi, the joints' velocities and classical accelerations at (q, v, a) in
    LOCAL_WORLD_ALIGNED, data.J, data.dJ, the centre of mass, its Jacobian, A_g).

Nothing of example-robot-data is committed: the package is installed at benchmark time.
"""

import json
import os
import re
import sys

import numpy as np
import pinocchio as pin

# name: (path under example-robot-data's robots/, free-floating root?)
ROBOTS = {
    "go2": ("go2_description/urdf/go2.urdf", True),
    "xarm7": ("xarm_description/urdf/xarm7.urdf", False),
    "g1": ("g1_description/urdf/g1_29dof_rev_1_0.urdf", True),
    "anymal": ("anymal_c_simple_description/urdf/anymal.urdf", True),
    "solo12": ("solo_description/robots/solo12.urdf", True),
    "a1": ("a1_description/urdf/a1.urdf", True),
    "hyq": ("hyq_description/robots/hyq_no_sensors.urdf", True),
    "z1": ("z1_description/urdf/z1.urdf", False),
    "talos": ("talos_data/robots/talos_reduced.urdf", True),
}
SAMPLES = 20


def robots_dir():
    import cmeel

    prefix = os.path.join(os.path.dirname(cmeel.__path__[0]), "cmeel.prefix")
    return os.path.join(prefix, "share", "example-robot-data", "robots")


def without_damping(text):
    """The URDF text with its <dynamics> elements (damping, friction) removed."""
    return re.sub(r"<dynamics\b[^>]*/>|<dynamics\b[^>]*>.*?</dynamics>", "", text, flags=re.S)


def rows(m):
    return [[float(x) for x in row] for row in np.asarray(m)]


def vector(v):
    return [float(x) for x in np.asarray(v).ravel()]


def placement(se3):
    return {"translation": vector(se3.translation), "rotation": rows(se3.rotation)}


def joint_entry(model, i):
    joint = model.joints[i]
    kind = joint.shortname()
    axes = {"X": [1.0, 0.0, 0.0], "Y": [0.0, 1.0, 0.0], "Z": [0.0, 0.0, 1.0]}
    if kind == "JointModelFreeFlyer":
        jtype, axis = "free_flyer", None
    elif kind in ("JointModelRX", "JointModelRY", "JointModelRZ"):
        jtype, axis = "revolute", axes[kind[-1]]
    elif kind in ("JointModelPX", "JointModelPY", "JointModelPZ"):
        jtype, axis = "prismatic", axes[kind[-1]]
    elif kind == "JointModelRevoluteUnaligned":
        jtype, axis = "revolute", vector(joint.extract().axis)
    elif kind == "JointModelPrismaticUnaligned":
        jtype, axis = "prismatic", vector(joint.extract().axis)
    else:
        sys.exit(f"public_robots.py: joint {model.names[i]} is a {kind}, not supported here")
    return {
        "name": model.names[i],
        "parent": int(model.parents[i]) - 1,
        "type": jtype,
        "axis": axis,
        "pinocchio_type": kind,
        "idx_q": joint.idx_q,
        "idx_v": joint.idx_v,
        "nq": joint.nq,
        "nv": joint.nv,
        "placement": placement(model.jointPlacements[i]),
    }


def body_entry(model, i):
    inertia = model.inertias[i]
    return {
        "joint": i - 1,
        "mass": float(inertia.mass),
        "com": vector(inertia.lever),
        "inertia_com": rows(inertia.inertia),
    }


def states(model, rng):
    """Seeded states: joints within their limits (or ±π), the base anywhere near the origin."""
    lower = model.lowerPositionLimit.copy()
    upper = model.upperPositionLimit.copy()
    with np.errstate(over="ignore", invalid="ignore"):
        bad = ~np.isfinite(lower) | ~np.isfinite(upper) | (upper - lower > 1e3)
    lower[bad], upper[bad] = -np.pi, np.pi
    for _ in range(SAMPLES):
        q = pin.neutral(model)
        for i in range(1, model.njoints):
            j = model.joints[i]
            if j.shortname() == "JointModelFreeFlyer":
                quaternion = rng.normal(size=4)
                quaternion /= np.linalg.norm(quaternion)
                q[j.idx_q : j.idx_q + 3] = rng.uniform(-1.0, 1.0, 3)
                q[j.idx_q + 3 : j.idx_q + 7] = quaternion
            else:
                lo, hi = lower[j.idx_q], upper[j.idx_q]
                q[j.idx_q] = rng.uniform(lo, hi)
        v = rng.uniform(-2.0, 2.0, model.nv)
        a = rng.uniform(-3.0, 3.0, model.nv)
        tau = rng.uniform(-5.0, 5.0, model.nv)
        yield q, v, a, tau


def sample(model, data, q, v, a, tau):
    out = {"q": vector(q), "v": vector(v), "a": vector(a), "tau": vector(tau)}
    out["rnea"] = vector(pin.rnea(model, data, q, v, a))
    out["nle"] = vector(pin.nonLinearEffects(model, data, q, v))
    out["gravity_torque"] = vector(pin.computeGeneralizedGravity(model, data, q))
    out["aba"] = vector(pin.aba(model, data, q, v, tau))
    mass = pin.crba(model, data, q)
    mass = np.triu(mass) + np.triu(mass, 1).T
    out["crba"] = rows(mass)
    out["coriolis_v"] = vector(pin.computeCoriolisMatrix(model, data, q, v) @ v)
    out["kinetic_energy"] = float(pin.computeKineticEnergy(model, data, q, v))
    out["potential_energy"] = float(pin.computePotentialEnergy(model, data, q))
    d_tau_dq, d_tau_dv, _ = pin.computeRNEADerivatives(model, data, q, v, a)
    out["dtau_dq"], out["dtau_dv"] = rows(d_tau_dq), rows(d_tau_dv)
    d_ddq_dq, d_ddq_dv, minv = pin.computeABADerivatives(model, data, q, v, tau)
    minv = np.triu(minv) + np.triu(minv, 1).T
    out["ddq_dq"], out["ddq_dv"], out["minv"] = rows(d_ddq_dq), rows(d_ddq_dv), rows(minv)
    d_ag = pin.dccrba(model, data, q, v)
    out["centroidal_bias"] = vector(np.asarray(d_ag) @ v)
    pin.computeJointJacobiansTimeVariation(model, data, q, v)
    out["joint_jacobians_world_pinocchio"] = rows(data.J)
    out["joint_jacobians_world_time_variation_pinocchio"] = rows(data.dJ)
    pin.forwardKinematics(model, data, q, v, a)
    frame = pin.ReferenceFrame.LOCAL_WORLD_ALIGNED
    joints = range(1, model.njoints)
    out["joint_placements"] = [placement(data.oMi[i]) for i in joints]
    out["joint_velocities_world"] = [vector(pin.getVelocity(model, data, i, frame)) for i in joints]
    out["joint_classical_accelerations_world"] = [
        vector(pin.getClassicalAcceleration(model, data, i, frame)) for i in joints
    ]
    out["center_of_mass"] = vector(pin.centerOfMass(model, data, q))
    out["com_jacobian"] = rows(pin.jacobianCenterOfMass(model, data, q))
    out["centroidal_momentum_matrix"] = rows(pin.ccrba(model, data, q, v))
    return out


def export(name, out_dir):
    if name not in ROBOTS:
        sys.exit(f"public_robots.py: unknown robot {name} (known: {' '.join(ROBOTS)})")
    relative, free = ROBOTS[name]
    source = os.path.join(robots_dir(), relative)
    if not os.path.isfile(source):
        sys.exit(f"public_robots.py: {source} not found (is example-robot-data installed?)")
    urdf = os.path.join(out_dir, f"{name}.urdf")
    with open(source) as f:
        text = without_damping(f.read())
    with open(urdf, "w") as f:
        f.write(text)
    model = (
        pin.buildModelFromUrdf(urdf, pin.JointModelFreeFlyer())
        if free
        else pin.buildModelFromUrdf(urdf)
    )
    data = model.createData()
    rng = np.random.default_rng(20261124)
    document = {
        "name": name,
        "urdf": relative,
        "source": "example-robot-data (PyPI), " + relative + ", damping and friction removed",
        "floating_base": free,
        "generator": "models/benches/pinocchio/public_robots.py",
        "model": {
            "nq": model.nq,
            "nv": model.nv,
            "gravity": vector(model.gravity.linear),
            "joints": [joint_entry(model, i) for i in range(1, model.njoints)],
            "bodies": [body_entry(model, i) for i in range(1, model.njoints)],
        },
        "samples": [sample(model, data, *state) for state in states(model, rng)],
    }
    with open(os.path.join(out_dir, f"{name}.json"), "w") as f:
        json.dump(document, f)
    print(f"{name}\t{model.nq}\t{model.nv}\t{'free' if free else 'fixed'}\t{urdf}")


def main():
    if len(sys.argv) < 3:
        sys.exit("usage: python public_robots.py OUT_DIR NAME...")
    out_dir = sys.argv[1]
    os.makedirs(out_dir, exist_ok=True)
    for name in sys.argv[2:]:
        export(name, out_dir)


if __name__ == "__main__":
    main()
