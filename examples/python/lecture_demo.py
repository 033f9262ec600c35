"""The lecture's demo in ten lines: compress to the ceiling's stop, then a plot of the lowest
det F and the energy split over time.  python3 lecture_demo.py [out.png] [steps]"""
import sys

import matplotlib.pyplot as plt

import invfree

out = sys.argv[1] if len(sys.argv) > 1 else "lecture_demo.png"
steps = int(sys.argv[2]) if len(sys.argv) > 2 else 300

# --- the ten lines ---
sim = invfree.Simulation(scene="compress")
t, min_det, energy = [], [], []
def record(s, report):
    t.append(s.time); min_det.append(s.det_f().min()); energy.append(s.energy())
sim.run(steps, callback=record)
fig, (a, b) = plt.subplots(2, 1, sharex=True, figsize=(7, 6))
a.plot(t, min_det); a.set_ylabel("min det F")
for key in ["kinetic", "elastic", "gravitational", "contact"]:
    b.plot(t, [e[key] for e in energy], label=key)
b.set_xlabel("t (s)"); b.set_ylabel("energy (J)"); b.legend(); fig.savefig(out, dpi=80)
# ---

print(f"{sim.name}: {sim.step_count} steps, t = {sim.time:.2f} s, "
      f"min det F over the run {min(min_det):.6f}, wrote {out}")
