"""A parameter sweep: the shear modulus mu of the compressed square (lambda kept), and how
far its triangles are squashed (the lowest det F over the run) at each.
python3 sweep_mu.py [out.png] [steps]"""
import sys

import matplotlib.pyplot as plt
import numpy as np

import invfree

out = sys.argv[1] if len(sys.argv) > 1 else "sweep_mu.png"
steps = int(sys.argv[2]) if len(sys.argv) > 2 else 300

base = invfree.Simulation(scene="compress")
mu0 = base.scene["material"]["mu"] if "mu" in base.scene["material"] else None
if mu0 is None:  # the scene gives E and nu: mu = E / (2 (1 + nu))
    m = base.scene["material"]
    mu0 = m["E"] / (2.0 * (1.0 + m["nu"]))

mus = mu0 * np.array([0.25, 0.5, 1.0, 2.0, 4.0])
fig, (a, b) = plt.subplots(1, 2, figsize=(11, 4))
lowest = []
for mu in mus:
    sim = invfree.Simulation(scene="compress", set={"material.mu": float(mu)})
    t, min_det = [], []
    sim.run(steps, callback=lambda s, r: t.append(s.time) or min_det.append(s.det_f().min()))
    lowest.append(min(min_det))
    a.plot(t, min_det, label=f"mu = {mu:.3g} Pa")
    print(f"mu {mu:.6g} Pa: min det F {lowest[-1]:.6f}")
a.set_xlabel("t (s)"); a.set_ylabel("min det F"); a.legend()
b.semilogx(mus, lowest, "o-"); b.set_xlabel("mu (Pa)"); b.set_ylabel("lowest det F over the run")
fig.tight_layout(); fig.savefig(out, dpi=80)
print(f"wrote {out}")
