#!/usr/bin/python3
"""The Table 6 fit done the obvious Python way, as a speed baseline.

    tools/scipy_baseline.py CONFIG

Same data (the config's data file plus its seeded noise is replaced by the
same Gaussian noise level from numpy), same symmetric equations of motion
(Eq. 6 with Cm_alpha, Cm_q, Cm_alpha_delta2, Cm_q_delta2), same free
parameters and starting guesses, same initial conditions from the first
samples: scipy.integrate.solve_ivp (RK45, rtol 1e-7, comparable to
fit3dof's RK4 at 0.01 s, 3e-5 deg) inside
scipy.optimize.least_squares (trust-region reflective, 2-point Jacobian).
Prints the fitted coefficients and the wall time as JSON. Uses Debian's
python3-scipy.
"""

import csv
import json
import math
import sys
import time

import numpy as np
from scipy.integrate import solve_ivp
from scipy.optimize import least_squares


def load(path):
    t, phi, theta, psi = [], [], [], []
    with open(path, newline="") as f:
        for row in csv.DictReader(f):
            t.append(float(row["t"]))
            phi.append(float(row["phi"]))
            theta.append(float(row["theta"]))
            psi.append(float(row["psi"]))
    return map(np.array, (t, phi, theta, psi))


def main():
    # The Table 6 constants (configs/report/table6_sigma*.yaml).
    area, d, ix, iy = 0.390, 0.7047, 0.0372, 0.244
    u, q = 4774.0, 150.4
    sigma = float(sys.argv[2]) if len(sys.argv) > 2 else 0.01
    t, phi_m, theta_m, psi_m = load(sys.argv[1])
    rng = np.random.default_rng(1)
    phi_m = phi_m + sigma * rng.standard_normal(len(t))
    theta_m = theta_m + sigma * rng.standard_normal(len(t))
    psi_m = psi_m + sigma * rng.standard_normal(len(t))
    deg = math.pi / 180.0
    ratio = ix / iy
    stiff = q * area * d / iy
    rate = stiff * d / (2.0 * u)

    def rhs(_, x, c1, c2, c5, c6):
        ph, phd, th, thd, ps, psd = x
        st, ct, sp, cp = math.sin(th), math.cos(th), math.sin(ps), math.cos(ps)
        p, qq, r = phd - psd * st, thd, psd * ct
        alpha, beta = cp * st, -sp
        d2 = alpha * alpha + beta * beta
        s = c1 * stiff + c5 * stiff * d2
        damp = (c2 + c6 * d2) * rate
        my = alpha * s + qq * damp
        mz = -beta * s + r * damp
        tt = st / ct
        return [phd,
                psd * thd * ct + mz * tt + (2 - ratio) * psd * thd * tt * st
                + ratio * phd * thd * tt,
                thd,
                my - (1 - ratio) * psd * psd * st * ct - ratio * phd * psd * ct,
                psd,
                mz / ct + (2 - ratio) * psd * thd * tt + ratio * phd * thd / ct]

    def residuals(x):
        c1, c2, c5, c6 = x[:4]
        x0 = [x[4] * deg, x[5] * deg, x[6] * deg, x[7] * deg, x[8] * deg,
              x[9] * deg]
        sol = solve_ivp(rhs, (t[0], t[-1]), x0, t_eval=t, rtol=1e-7,
                        atol=1e-10, args=(c1, c2, c5, c6))
        if not sol.success or sol.y.shape[1] != len(t):
            return np.full(3 * len(t), 1e3)
        ph = sol.y[0] / deg
        ph = ph - 360.0 * np.round((ph - phi_m) / 360.0)
        return np.concatenate([(ph - phi_m) / sigma,
                               (sol.y[2] / deg - theta_m) / sigma,
                               (sol.y[4] / deg - psi_m) / sigma])

    def slope(y):
        return (y[1] - y[0]) / (t[1] - t[0])

    start = [-0.2, 0.0, 0.0, 0.0, phi_m[0], slope(phi_m), theta_m[0],
             slope(theta_m), psi_m[0], slope(psi_m)]
    began = time.time()
    fit = least_squares(residuals, start, method="trf", x_scale="jac",
                        max_nfev=200)
    elapsed = time.time() - began
    e = math.sqrt(np.sum(fit.fun ** 2) / (3 * len(t) - len(start)))
    print(json.dumps({
        "seconds": elapsed,
        "evaluations": int(fit.nfev),
        "converged": bool(fit.success) and e < 2.0,
        "probable_error": e,
        "Cm_alpha": fit.x[0], "Cm_q": fit.x[1],
        "Cm_alpha_delta2": fit.x[2], "Cm_q_delta2": fit.x[3],
    }))


if __name__ == "__main__":
    main()
