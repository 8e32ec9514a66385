#!/usr/bin/env python3
"""Pinocchio's values for the frame and centroidal tests of the runtime reference.

    python3 dynamics-runtime/tools/pinocchio_frames.py     # needs pin (pip install pin==4.1.0)

Builds, joint by joint in Pinocchio, the free-floating tree of `floating_tree` in
dynamics-runtime/src/reference/frame_tests.rs (the same declared numbers: a free base, a
revolute arm on an unaligned axis with a turned placement, a slider on an unaligned axis, a
hand welded to the arm, whose inertia Pinocchio appends to the arm's joint, and the frames
`imu`, `tip`, `tool` on the hand and `marker` on the ground), evaluates at the state of
`tree_state` what the reference computes, and prints it as the Rust constants of
dynamics-runtime/src/reference/pinocchio_frames.rs (redirect the output there):

- oMf of `tool` (updateFramePlacements);
- getFrameJacobian of `tool` and of `tip`, LOCAL_WORLD_ALIGNED, and of `tool`, LOCAL;
- getFrameVelocity and getFrameClassicalAcceleration of `tool`, LOCAL_WORLD_ALIGNED;
- getFrameJacobianTimeVariation (LOCAL_WORLD_ALIGNED) times v, of `tool` and `tip`;
- hg and dhg (computeCentroidalMomentumTimeVariation), and dAg v (dccrba).

Deterministic; takes a second.
"""
import numpy as np
import pinocchio as pin

# The declared numbers of `floating_tree` and `tree_state`.
I_BODY = np.array([[0.03, 0.002, 0.0], [0.002, 0.02, 0.001], [0.0, 0.001, 0.04]])
TURNED = pin.rpy.rpyToMatrix(0.3, -0.2, 0.5)  # nalgebra's from_euler_angles(roll, pitch, yaw)
TILTED = pin.rpy.rpyToMatrix(-0.4, 0.7, 0.1)
Q = np.array([0.1, -0.2, 0.3, 0.2, -0.1, 0.3, 0.9273618495495703, 0.7, -0.2])
V = np.array([0.5, -1.0, 0.2, 1.5, -0.3, 0.8, 2.0, -1.0])
A = np.array([1.0, 0.3, -0.5, 0.2, 0.9, -1.1, 0.4, 2.0])


def rz(angle):
    c, s = np.cos(angle), np.sin(angle)
    return np.array([[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]])


def unit(v):
    v = np.array(v, dtype=float)
    return v / np.linalg.norm(v)


def inertia(mass, com):
    return pin.Inertia(mass, np.array(com), I_BODY)


def build():
    model = pin.Model()
    base = model.addJoint(0, pin.JointModelFreeFlyer(), pin.SE3.Identity(), "float")
    model.appendBodyToJoint(base, inertia(3.0, [0.02, -0.01, 0.05]), pin.SE3.Identity())
    arm = model.addJoint(base, pin.JointModelRevoluteUnaligned(unit([0.2, 1.0, -0.3])),
                         pin.SE3(TURNED, np.array([0.2, 0.0, 0.1])), "hinge")
    model.appendBodyToJoint(arm, inertia(1.2, [0.1, 0.05, -0.02]), pin.SE3.Identity())
    slider = model.addJoint(arm, pin.JointModelPrismaticUnaligned(unit([1.0, 0.3, 0.0])),
                            pin.SE3(np.eye(3), np.array([0.3, 0.0, 0.0])), "slide")
    model.appendBodyToJoint(slider, inertia(0.5, [0.03, 0.0, 0.01]), pin.SE3.Identity())
    hand_in_arm = pin.SE3(TILTED, np.array([0.0, 0.35, 0.05]))
    model.appendBodyToJoint(arm, inertia(0.4, [0.0, 0.02, 0.04]), hand_in_arm)
    frames = {}
    for name, joint, placement in [
        ("imu", base, pin.SE3(rz(0.7), np.array([0.05, 0.02, -0.03]))),
        ("tip", slider, pin.SE3(np.eye(3), np.array([0.1, -0.02, 0.03]))),
        ("tool", arm, hand_in_arm * pin.SE3(TURNED, np.array([0.02, 0.15, -0.01]))),
        ("marker", 0, pin.SE3(rz(-1.1), np.array([1.0, -2.0, 0.5]))),
    ]:
        frames[name] = model.addFrame(pin.Frame(name, joint, placement, pin.FrameType.OP_FRAME))
    return model, frames


def rust(name, value):
    value = np.asarray(value)
    if value.ndim == 1:
        body = ", ".join(repr(float(x)) for x in value)
        return f"pub(super) const {name}: [f64; {len(value)}] = [{body}];"
    rows = ",\n    ".join("[" + ", ".join(repr(float(x)) for x in row) + "]" for row in value)
    return (f"pub(super) const {name}: [[f64; {value.shape[1]}]; {value.shape[0]}] = [\n"
            f"    {rows},\n];")


def main():
    model, frames = build()
    data = model.createData()
    lwa, local = pin.ReferenceFrame.LOCAL_WORLD_ALIGNED, pin.ReferenceFrame.LOCAL
    tool, tip = frames["tool"], frames["tip"]
    pin.forwardKinematics(model, data, Q, V, A)
    pin.updateFramePlacements(model, data)
    pin.computeJointJacobians(model, data, Q)
    out = [
        rust("TOOL_ROTATION", data.oMf[tool].rotation),
        rust("TOOL_ORIGIN", data.oMf[tool].translation),
        rust("TOOL_JACOBIAN", pin.getFrameJacobian(model, data, tool, lwa)),
        rust("TOOL_JACOBIAN_LOCAL", pin.getFrameJacobian(model, data, tool, local)),
        rust("TIP_JACOBIAN", pin.getFrameJacobian(model, data, tip, lwa)),
        rust("TOOL_VELOCITY", pin.getFrameVelocity(model, data, tool, lwa).vector),
        rust("TOOL_CLASSICAL_ACCELERATION",
             pin.getFrameClassicalAcceleration(model, data, tool, lwa).vector),
    ]
    pin.computeJointJacobiansTimeVariation(model, data, Q, V)
    out += [
        rust("TOOL_JDOT_V", pin.getFrameJacobianTimeVariation(model, data, tool, lwa) @ V),
        rust("TIP_JDOT_V", pin.getFrameJacobianTimeVariation(model, data, tip, lwa) @ V),
    ]
    pin.computeCentroidalMomentumTimeVariation(model, data, Q, V, A)
    out += [rust("HG", data.hg.vector), rust("DHG", data.dhg.vector)]
    pin.dccrba(model, data, Q, V)
    out.append(rust("DAG_V", data.dAg @ V))
    print(f"//! Pinocchio {pin.__version__}'s values for the floating tree of `frame_tests`, written by")
    print("//! `python3 dynamics-runtime/tools/pinocchio_frames.py` (its docstring says what each is);")
    print("//! matrices by rows, six-vectors linear first.")
    print()
    print("\n".join(out))


if __name__ == "__main__":
    main()
