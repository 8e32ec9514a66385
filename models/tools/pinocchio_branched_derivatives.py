#!/usr/bin/env python3
"""Writes tests/data/pinocchio_ext/branched_derivatives.json: Pinocchio's derivatives of the
dynamics of the test robot tests/data/urdf/branched.urdf on a free-flyer root (a branched
tree with a prismatic joint, 13 degrees of freedom, 14 coordinates), in the format of the other
*_derivatives.json files (read by tests/generated_derivatives.rs):
computeRNEADerivatives(q, v, a) -> dtau_dq, dtau_dv; computeABADerivatives(q, v, tau) ->
ddq_dq, ddq_dv and minv (ddq_dtau, its upper triangle mirrored). q-derivatives in the
tangent space: column j is the derivative along q (+) t e_j, the free flyer's increment
in its body frame, ordered like v.

Run from the repository root, with Pinocchio installed (PyPI package `pin`; the file was
written with pin 4.1.0), e.g. with the comparison's environment:

    models/benches/pinocchio/venv/bin/python models/tools/pinocchio_branched_derivatives.py

The samples come from a fixed seed (its own, so the states differ from branched.json's),
with the states drawn as pinocchio_branched.py draws them.
"""
import json
import os
import sys

import numpy as np
import pinocchio as pin

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from pinocchio_branched import free_flyer_model, random_state, rows, symmetric, vector  # noqa: E402

ROOT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..")
OUT = os.path.join(ROOT, "tests", "data", "pinocchio_ext", "branched_derivatives.json")
SAMPLES = 20
SEED = 20261129


def sample(model, data, rng):
    q, v, a, tau = random_state(model, rng)
    dtau_dq, dtau_dv, _ = pin.computeRNEADerivatives(model, data, q, v, a)
    dtau_dq, dtau_dv = np.copy(dtau_dq), np.copy(dtau_dv)
    ddq_dq, ddq_dv, minv = pin.computeABADerivatives(model, data, q, v, tau)
    return {
        "q": vector(q),
        "v": vector(v),
        "a": vector(a),
        "tau": vector(tau),
        "dtau_dq": rows(dtau_dq),
        "dtau_dv": rows(dtau_dv),
        "ddq_dq": rows(ddq_dq),
        "ddq_dv": rows(ddq_dv),
        "minv": symmetric(minv),
    }


def main():
    model, data = free_flyer_model()
    rng = np.random.default_rng(SEED)
    out = {
        "name": "branched",
        "generator": f"Pinocchio {pin.__version__} (numpy {np.__version__}, "
                     "models/tools/pinocchio_branched_derivatives.py): "
                     "computeRNEADerivatives(q, v, a) dtau_dq, dtau_dv; "
                     "computeABADerivatives(q, v, tau) ddq_dq, ddq_dv and minv (= ddq_dtau, "
                     "its upper triangle mirrored). d/dq in the tangent space (q ⊕ δ, δ "
                     "ordered like v, the free flyer's in its body frame); the URDF's damping "
                     "left out, as Pinocchio's algorithms leave it out.",
        "samples": [sample(model, data, rng) for _ in range(SAMPLES)],
    }
    with open(OUT, "w") as f:
        json.dump(out, f)
        f.write("\n")


if __name__ == "__main__":
    main()
