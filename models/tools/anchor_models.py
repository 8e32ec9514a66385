#!/usr/bin/env python3
"""Writes the anchor mechanisms (models/src/anchors.rs) and their URDF twins (models/urdf/)
from the numbers of the Pinocchio test vectors in tests/data/pinocchio/.

Run from the repository root: python3 models/tools/anchor_models.py
The numbers are the published model parameters; the text is ours.
"""
import json
import math
import os
import sys

VECTORS = os.path.join(os.path.dirname(__file__), "..", "..", "tests", "data", "pinocchio")
MODELS = [
    ("pendulum", "Pendulum", "The seed's uniform rod (m = 2 kg, L = 0.6 m) pivoted at one end, gravity −y.",
     ["rod"]),
    ("double_pendulum", "DoublePendulum", "Two uniform rods, 1.5 kg / 0.5 m and 1.0 kg / 0.4 m, gravity −y.",
     ["upper_rod", "lower_rod"]),
    ("planar3", "Planar3", "A planar three-link chain with offset mass centres and non-diagonal inertias.",
     ["link1", "link2", "link3"]),
    ("ur5", "Ur5", "Universal Robots UR5 (parameters of example-robot-data's ur5_robot.urdf).",
     ["shoulder_link", "upper_arm_link", "forearm_link", "wrist_1_link", "wrist_2_link", "wrist_3_link"]),
    ("panda", "Panda", "Franka Emika Panda arm, fingers fixed (parameters of example-robot-data's panda.urdf).",
     ["panda_link1", "panda_link2", "panda_link3", "panda_link4", "panda_link5", "panda_link6", "panda_link7"]),
]


def num(x):
    r = repr(float(x))
    return r


def vec(v):
    return "[" + ", ".join(num(x) for x in v) + "]"


def mat(m):
    return "[" + ", ".join(vec(r) for r in m) + "]"


def is_identity(m):
    return all(m[i][j] == (1.0 if i == j else 0.0) for i in range(3) for j in range(3))


def axis(a):
    names = {(1.0, 0.0, 0.0): "x", (0.0, 1.0, 0.0): "y", (0.0, 0.0, 1.0): "z",
             (-1.0, 0.0, 0.0): "-x", (0.0, -1.0, 0.0): "-y", (0.0, 0.0, -1.0): "-z"}
    return names.get(tuple(a), vec(a))


def triangle_ok(inertia):
    import numpy as np
    w = np.linalg.eigvalsh(np.array(inertia))
    return w[0] + w[1] >= w[2] - 1e-9 * sum(w)


def dsl(key, type_name, doc, links, model):
    out = []
    out.append("mechanism! {")
    out.append(f"    /// {doc}")
    out.append("    ///")
    out.append("    /// Declared from the numbers of `tests/data/pinocchio/" + key + ".json`.")
    out.append(f"    pub struct {type_name};")
    out.append(f"    gravity: {vec(model['gravity'])};")
    if not all(triangle_ok(b["inertia_com"]) for b in model["bodies"]):
        out.append("    // The published inertias of this model violate I1 + I2 ≥ I3 (laminae with products of inertia).")
        out.append("    allow: [triangle_inequality];")
    for link, body in zip(links, model["bodies"]):
        out.append("")
        out.append(f"    body {link} {{")
        out.append(f"        mass: {num(body['mass'])},")
        out.append(f"        com: {vec(body['com'])},")
        out.append(f"        inertia: {mat(body['inertia_com'])},")
        out.append("    }")
    for joint in model["joints"]:
        parent = "ground" if joint["parent"] < 0 else links[joint["parent"]]
        child = links[model["joints"].index(joint)]
        kind = {"revolute": "revolute", "prismatic": "prismatic"}[joint["type"]]
        fields = [f"axis: {axis(joint['axis'])}"]
        t = joint["placement"]["translation"]
        if any(x != 0.0 for x in t):
            fields.append(f"at: {vec(t)}")
        r = joint["placement"]["rotation"]
        if not is_identity(r):
            fields.append(f"rotation: {mat(r)}")
        out.append("")
        out.append(f"    joint {joint['name']}: {kind}({parent} -> {child}) {{")
        for f in fields:
            out.append(f"        {f},")
        out.append("    }")
    out.append("}")
    return "\n".join(out)


def rpy_of(r):
    # R = Rz(y) Ry(p) Rx(r)
    pitch = math.atan2(-r[2][0], math.hypot(r[0][0], r[1][0]))
    roll = math.atan2(r[2][1], r[2][2])
    yaw = math.atan2(r[1][0], r[0][0])
    return [roll, pitch, yaw]


def urdf(key, links, model):
    out = ['<?xml version="1.0"?>', f'<robot name="{key}">', '  <link name="base"/>']
    for link, body in zip(links, model["bodies"]):
        i = body["inertia_com"]
        out.append(f'  <link name="{link}">')
        out.append('    <inertial>')
        out.append(f'      <origin xyz="{" ".join(num(x) for x in body["com"])}" rpy="0 0 0"/>')
        out.append(f'      <mass value="{num(body["mass"])}"/>')
        out.append(f'      <inertia ixx="{num(i[0][0])}" ixy="{num(i[0][1])}" ixz="{num(i[0][2])}" '
                   f'iyy="{num(i[1][1])}" iyz="{num(i[1][2])}" izz="{num(i[2][2])}"/>')
        out.append('    </inertial>')
        out.append('  </link>')
    for idx, joint in enumerate(model["joints"]):
        parent = "base" if joint["parent"] < 0 else links[joint["parent"]]
        p = joint["placement"]
        out.append(f'  <joint name="{joint["name"]}" type="{joint["type"]}">')
        out.append(f'    <parent link="{parent}"/>')
        out.append(f'    <child link="{links[idx]}"/>')
        out.append(f'    <origin xyz="{" ".join(num(x) for x in p["translation"])}" '
                   f'rpy="{" ".join(num(x) for x in rpy_of(p["rotation"]))}"/>')
        out.append(f'    <axis xyz="{" ".join(num(x) for x in joint["axis"])}"/>')
        out.append('    <limit lower="-6.28" upper="6.28" effort="100" velocity="10"/>')
        out.append('  </joint>')
    out.append('</robot>')
    return "\n".join(out) + "\n"


def main():
    root = os.path.join(os.path.dirname(__file__), "..")
    parts = ["//! Anchor models: the mechanisms of the Pinocchio test vectors, declared in the language.",
             "//!",
             "//! Written by `models/tools/anchor_models.py` from `tests/data/pinocchio/*.json`; the",
             "//! URDF twins in `models/urdf/` carry the same numbers.",
             "",
             "use dynamics_runtime::mechanism;",
             ""]
    for key, type_name, doc, links in MODELS:
        with open(os.path.join(VECTORS, key + ".json")) as f:
            model = json.load(f)["model"]
        parts.append(dsl(key, type_name, doc, links, model))
        parts.append("")
        with open(os.path.join(root, "urdf", key + ".urdf"), "w") as f:
            f.write(urdf(key, links, model))
    with open(os.path.join(root, "src", "anchors.rs"), "w") as f:
        f.write("\n".join(parts))


if __name__ == "__main__":
    sys.exit(main())
