"""A student's own implicit Euler step against invfree's, step by step.

The student's step is chapter 6 of the solid-sim-tutorial written the way its
time_integrator.py is: the incremental potential of inertia, neo-Hookean triangles, gravity
and the ground's IPC barrier, minimised by Newton with each triangle's Hessian projected to
PSD (here by numpy's eigh on the 6x6 block, not invfree's diagonal space: a different path to
the same minimiser), a line search that keeps det F > 0 and every node above the ground, and
the stop |p|inf / h < tol. The mesh, masses and scene values are read from invfree, so the
two solve the same problem; from invfree's state each step, both take one step and the
difference is printed. Both converge tightly (tol 1e-7 m/s) so that what is left is the
solvers' rounding, not their tolerance.

python3 student_step.py [out.png] [steps]"""
import sys

import matplotlib.pyplot as plt
import numpy as np

import invfree

out = sys.argv[1] if len(sys.argv) > 1 else "student_step.png"
steps = int(sys.argv[2]) if len(sys.argv) > 2 else 80
TOL = 1e-7

# compress without the ceiling and without friction: what chapter 6's script has.
sim = invfree.Simulation(scene="compress", set={
    "ceiling.enabled": False, "ground.friction": 0.0, "time.tol": TOL})
scene = sim.scene
material = scene["material"]
if "mu" in material:
    mu, lam = material["mu"], material["lambda"]
else:
    E, nu = material["E"], material["nu"]
    mu, lam = E / (2 * (1 + nu)), E * nu / ((1 + nu) * (1 - 2 * nu))
h, g = scene["time"]["h"], np.array(scene["gravity"]["g"])
ground_y, dhat, kappa = scene["ground"]["y"], scene["barrier"]["dhat"], scene["barrier"]["kappa"]
contact_area = scene["mesh"]["side"] / scene["mesh"]["n_seg"]
tri, rest, mass = sim.triangles, sim.rest, np.repeat(sim.node_mass, 2)

# Per triangle: the rest shape's inverse and area, and dvec(F)/dx (4 x 6; vec row-major).
Dm = np.stack([rest[tri[:, 1]] - rest[tri[:, 0]], rest[tri[:, 2]] - rest[tri[:, 0]]], axis=2)
B = np.linalg.inv(Dm)
area = 0.5 * np.abs(np.linalg.det(Dm))
dFdx = np.zeros((len(tri), 4, 6))
for i in range(2):
    for j in range(2):
        dFdx[:, 2 * i + j, 0 + i] = -(B[:, 0, j] + B[:, 1, j])
        dFdx[:, 2 * i + j, 2 + i] = B[:, 0, j]
        dFdx[:, 2 * i + j, 4 + i] = B[:, 1, j]
dofs = np.stack([2 * tri[:, a] + c for a in range(3) for c in range(2)], axis=1)  # (T, 6)


def deformation(x):
    X = x.reshape(-1, 2)
    Ds = np.stack([X[tri[:, 1]] - X[tri[:, 0]], X[tri[:, 2]] - X[tri[:, 0]]], axis=2)
    return Ds @ B


def energy(x, x_tilde):
    F = deformation(x)
    J = np.linalg.det(F)
    if np.any(J <= 0):
        return np.inf
    lnJ = np.log(J)
    psi = 0.5 * mu * (np.sum(F * F, axis=(1, 2)) - 2) - mu * lnJ + 0.5 * lam * lnJ**2
    d = x[1::2] - ground_y
    if np.any(d <= 0):
        return np.inf
    s = d[d < dhat] / dhat
    barrier = np.sum(contact_area * dhat * kappa / 2 * (s - 1) * np.log(s))
    gravity = -np.sum(mass * np.tile(g, len(x) // 2) * x)
    inertia = 0.5 * np.sum(mass * (x - x_tilde) ** 2)
    return inertia + h * h * (np.sum(area * psi) + gravity + barrier)


def gradient_hessian(x, x_tilde):
    n = len(x)
    F = deformation(x)
    J = np.linalg.det(F)
    lnJ = np.log(J)
    cof = np.stack([F[:, 1, 1], -F[:, 1, 0], -F[:, 0, 1], F[:, 0, 0]], axis=1)  # dJ/dF
    P = mu * F.reshape(-1, 4) + ((lam * lnJ - mu) / J)[:, None] * cof
    K = np.zeros((4, 4))
    K[0, 3] = K[3, 0] = 1.0
    K[1, 2] = K[2, 1] = -1.0
    dPdF = (mu * np.eye(4) + ((lam * (1 - lnJ) + mu) / J**2)[:, None, None]
            * cof[:, :, None] * cof[:, None, :] + ((lam * lnJ - mu) / J)[:, None, None] * K)
    ge = area[:, None] * np.einsum("tki,tk->ti", dFdx, P)
    He = area[:, None, None] * np.einsum("tki,tkl,tlj->tij", dFdx, dPdF, dFdx)
    w, V = np.linalg.eigh(He)  # the projection to PSD, per triangle
    He = np.einsum("tij,tj,tkj->tik", V, np.maximum(w, 0.0), V)
    grad = mass * (x - x_tilde) - h * h * mass * np.tile(g, n // 2)
    hess = np.diag(mass).astype(float)
    np.add.at(grad, dofs, h * h * ge)
    np.add.at(hess, (dofs[:, :, None], dofs[:, None, :]), h * h * He)
    d = x[1::2] - ground_y
    near = np.nonzero(d < dhat)[0]
    s = d[near] / dhat
    grad[2 * near + 1] += h * h * contact_area * kappa / 2 * (np.log(s) + (s - 1) / s)
    hess[2 * near + 1, 2 * near + 1] += (h * h * contact_area * kappa / (2 * dhat)
                                         * (1 / s + 1 / s**2))
    return grad, hess


def student_step(x, v):
    """One implicit Euler step from (x, v), both (nodes, 2); returns the new positions."""
    x_n = x.reshape(-1)
    x_tilde = x_n + h * v.reshape(-1)
    x = x_n.copy()
    for _ in range(100):
        grad, hess = gradient_hessian(x, x_tilde)
        p = np.linalg.solve(hess, -grad)
        if np.max(np.abs(p)) / h < TOL:
            break
        alpha = 1.0
        e0 = energy(x, x_tilde)
        while energy(x + alpha * p, x_tilde) > e0:  # inf where inverted or below the ground
            alpha *= 0.5
        x = x + alpha * p
    return x.reshape(-1, 2)


diffs, times, lowest_y = [], [], np.inf
for k in range(steps):
    mine = student_step(sim.x, sim.v)
    sim.step()
    diffs.append(np.max(np.abs(mine - sim.x)))
    times.append(sim.time)
    lowest_y = min(lowest_y, sim.x[:, 1].min())
print(f"{steps} steps: the student's step and invfree's differ by at most {max(diffs):.3g} m "
      f"(lowest y over the run {lowest_y:.4f} m, ground at {ground_y} m)")
fig, ax = plt.subplots(figsize=(7, 4))
ax.semilogy(times, np.maximum(diffs, 1e-18))
ax.set_xlabel("t (s)"); ax.set_ylabel("max |x_student - x_invfree| (m)")
ax.set_title("one step from the same state, every step")
fig.tight_layout(); fig.savefig(out, dpi=80)
print(f"wrote {out}")
