#!/usr/bin/env python3
"""Writes tests/data/pinocchio/branched.json: Pinocchio's model and dynamics of the test
robot tests/data/urdf/branched.urdf on a free-flyer root, in the format of the anchor files
(tests/data/pinocchio/*.json, read by dynamics_tests::anchors), plus the joint limits,
damping and friction Pinocchio reads from the file.

Run from the repository root, with Pinocchio installed (PyPI package `pin`; the file was
written with pin 4.1.0):

    python3 -m venv /tmp/pinvenv && /tmp/pinvenv/bin/pip install pin
    /tmp/pinvenv/bin/python models/tools/pinocchio_branched.py

The samples are drawn from a fixed seed, so a run reproduces the file (up to Pinocchio's
and numpy's versions, recorded in `generator`).
"""
import json
import os

import numpy as np
import pinocchio as pin

ROOT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..")
URDF = os.path.join(ROOT, "tests", "data", "urdf", "branched.urdf")
OUT = os.path.join(ROOT, "tests", "data", "pinocchio", "branched.json")
SAMPLES = 20
SEED = 20261125


def rows(m):
    return [[float(x) for x in row] for row in np.asarray(m)]


def vector(v):
    return [float(x) for x in np.asarray(v).ravel()]


def symmetric(m):
    m = np.asarray(m)
    return rows(np.triu(m) + np.triu(m, 1).T)


def joint_entry(model, i):
    joint = model.joints[i]
    short = joint.shortname()
    placement = model.jointPlacements[i]
    entry = {
        "name": model.names[i],
        "parent": int(model.parents[i]) - 1,
        "pinocchio_type": short,
        "idx_q": int(joint.idx_q),
        "idx_v": int(joint.idx_v),
        "nq": int(joint.nq),
        "nv": int(joint.nv),
        "placement": {
            "translation": vector(placement.translation),
            "rotation": rows(placement.rotation),
        },
    }
    if short == "JointModelFreeFlyer":
        entry["type"] = "free_flyer"
    elif short.startswith("JointModelR"):
        entry["type"] = "revolute"
    elif short.startswith("JointModelP"):
        entry["type"] = "prismatic"
    else:
        raise ValueError(f"joint {model.names[i]}: unexpected type {short}")
    if entry["type"] != "free_flyer":
        if short.endswith("Unaligned"):
            axis = joint.extract().axis
        else:
            axis = {"X": [1.0, 0.0, 0.0], "Y": [0.0, 1.0, 0.0], "Z": [0.0, 0.0, 1.0]}[short[-1]]
        entry["axis"] = vector(axis)
    return entry


def body_entry(model, i):
    inertia = model.inertias[i]
    return {
        "joint": i - 1,
        "mass": float(inertia.mass),
        "com": vector(inertia.lever),
        "inertia_com": rows(inertia.inertia),
    }


def random_configuration(model, rng):
    q = np.zeros(model.nq)
    for i in range(1, model.njoints):
        joint = model.joints[i]
        if joint.shortname() == "JointModelFreeFlyer":
            quaternion = rng.normal(size=4)
            quaternion /= np.linalg.norm(quaternion)
            q[joint.idx_q:joint.idx_q + 3] = rng.uniform(-1.0, 1.0, 3)
            q[joint.idx_q + 3:joint.idx_q + 7] = quaternion
        else:
            lower = model.lowerPositionLimit[joint.idx_q]
            upper = model.upperPositionLimit[joint.idx_q]
            q[joint.idx_q] = rng.uniform(lower, upper)
    return q


def random_state(model, rng):
    """A configuration and velocities, accelerations and joint forces, drawn in that order."""
    q = random_configuration(model, rng)
    v = rng.uniform(-2.0, 2.0, model.nv)
    a = rng.uniform(-3.0, 3.0, model.nv)
    tau = rng.uniform(-5.0, 5.0, model.nv)
    return q, v, a, tau


def free_flyer_model():
    """Pinocchio's model of branched.urdf on a free-flyer root, and its data."""
    model = pin.buildModelFromUrdf(URDF, pin.JointModelFreeFlyer())
    return model, model.createData()


def sample(model, data, rng):
    q, v, a, tau = random_state(model, rng)
    return {
        "q": vector(q),
        "v": vector(v),
        "a": vector(a),
        "tau": vector(tau),
        "rnea": vector(pin.rnea(model, data, q, v, a)),
        "crba": symmetric(pin.crba(model, data, q)),
        "nle": vector(pin.nonLinearEffects(model, data, q, v)),
        "gravity_torque": vector(pin.computeGeneralizedGravity(model, data, q)),
        "aba": vector(pin.aba(model, data, q, v, tau)),
        "coriolis": rows(pin.computeCoriolisMatrix(model, data, q, v)),
        "kinetic_energy": float(pin.computeKineticEnergy(model, data, q, v)),
        "potential_energy": float(pin.computePotentialEnergy(model, data, q)),
    }


def main():
    model, data = free_flyer_model()
    rng = np.random.default_rng(SEED)
    out = {
        "name": "branched",
        "urdf": "tests/data/urdf/branched.urdf",
        "source": "this repository (a test robot)",
        "floating_base": True,
        "generator": {
            "pinocchio": pin.__version__,
            "numpy": np.__version__,
            "script": "models/tools/pinocchio_branched.py",
        },
        "conventions": {
            "joint_order": "joints listed in Pinocchio order (depth first over the URDF tree, a "
                           "link's child joints sorted by name); 'parent' is the index into this "
                           "list, -1 = world.",
            "placement": "pose of the joint frame in the parent joint frame at zero motion: "
                         "x_parent = rotation @ x_joint + translation (jointPlacements). Links "
                         "attached through fixed joints are merged into the moving body.",
            "body": "body i moves with joint i; com and inertia_com (about the mass centre) in "
                    "its frame.",
            "free_flyer": "q = [x, y, z, qx, qy, qz, qw], v = [v_lin, omega] in the body frame.",
            "samples": "rnea, crba (symmetrised), nonLinearEffects, computeGeneralizedGravity, "
                       "aba, computeCoriolisMatrix, kinetic and potential energy. Pinocchio's "
                       "algorithms leave the model's damping out.",
            "limits": "Pinocchio's lowerPositionLimit and upperPositionLimit (per q), "
                      "velocityLimit, effortLimit, damping and friction (per v); unbounded "
                      "entries are +-1.7976931348623157e308 (the largest double).",
        },
        "model": {
            "nq": int(model.nq),
            "nv": int(model.nv),
            "gravity": vector(model.gravity.linear),
            "joints": [joint_entry(model, i) for i in range(1, model.njoints)],
            "bodies": [body_entry(model, i) for i in range(1, model.njoints)],
            "frames": [frame.name for frame in model.frames],
            "lower_position_limit": vector(model.lowerPositionLimit),
            "upper_position_limit": vector(model.upperPositionLimit),
            "velocity_limit": vector(model.velocityLimit),
            "effort_limit": vector(model.effortLimit),
            "damping": vector(model.damping),
            "friction": vector(model.friction),
        },
        "samples": [sample(model, data, rng) for _ in range(SAMPLES)],
    }
    with open(OUT, "w") as f:
        json.dump(out, f, indent=1)
        f.write("\n")


if __name__ == "__main__":
    main()
