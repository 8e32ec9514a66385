#!/usr/bin/env python3
"""Writes a URDF of many links welded through fixed joints, for the cost of validation
(BENCHMARKS.md, "Validation cost"; issue 21).

    python3 models/tools/welded_urdf.py chain 20000 > /tmp/chain.urdf
    python3 models/tools/welded_urdf.py star 20000 > /tmp/star.urdf
    target/release/dynamics-codegen /tmp/chain.urdf --ops

- `chain N`: links link0 ... link{N-1}, each the child of the one before (link0 of the
  root `base`); every joint is fixed except two revolute joints, at a third and at two
  thirds of the chain, so the mechanism has two degrees of freedom and three welded groups
  thousands of links deep.
- `star N`: N links each welded directly to `base`, which a revolute joint moves relative
  to a root link `world`: one welded group of N + 1 links, one level deep.

Each link is a 0.1 kg rod-like body, offset 1 cm from its parent, with a small diagonal
inertia; the numbers are physical, so the file is valid and compiles.
"""
import sys


def link(name):
    return (
        f'  <link name="{name}">\n'
        f'    <inertial>\n'
        f'      <origin xyz="0.005 0 0" rpy="0 0 0"/>\n'
        f'      <mass value="0.1"/>\n'
        f'      <inertia ixx="1e-5" ixy="0" ixz="0" iyy="2e-5" iyz="0" izz="2e-5"/>\n'
        f'    </inertial>\n'
        f'  </link>\n'
    )


def joint(name, kind, parent, child, xyz):
    axis = '    <axis xyz="0 0 1"/>\n' if kind == "revolute" else ""
    limit = (
        '    <limit lower="-3.14" upper="3.14" effort="10" velocity="5"/>\n'
        if kind == "revolute"
        else ""
    )
    return (
        f'  <joint name="{name}" type="{kind}">\n'
        f'    <parent link="{parent}"/>\n'
        f'    <child link="{child}"/>\n'
        f'    <origin xyz="{xyz}" rpy="0 0 0"/>\n'
        f"{axis}{limit}"
        f"  </joint>\n"
    )


def chain(n):
    parts = [link("base")]
    moving = {n // 3, 2 * n // 3}
    for i in range(n):
        name = f"link{i}"
        parent = "base" if i == 0 else f"link{i - 1}"
        kind = "revolute" if i in moving else "fixed"
        parts.append(link(name))
        parts.append(joint(f"joint{i}", kind, parent, name, "0.01 0 0"))
    return parts


def star(n):
    parts = [link("world"), link("base")]
    parts.append(joint("hinge", "revolute", "world", "base", "0 0 0"))
    for i in range(n):
        name = f"link{i}"
        parts.append(link(name))
        parts.append(joint(f"joint{i}", "fixed", "base", name, f"0.01 {i * 1e-4:.4f} 0"))
    return parts


def main():
    if len(sys.argv) != 3 or sys.argv[1] not in ("chain", "star"):
        sys.exit("usage: welded_urdf.py chain|star N")
    n = int(sys.argv[2])
    parts = chain(n) if sys.argv[1] == "chain" else star(n)
    sys.stdout.write('<?xml version="1.0"?>\n<robot name="welded">\n')
    sys.stdout.write("".join(parts))
    sys.stdout.write("</robot>\n")


if __name__ == "__main__":
    main()
