"""
Tutorial: rock a block, change its COR, watch it overturn
=========================================================

A lesson for a class, about 15 minutes. Every cell runs in a second; change the numbers
and run it again. (This script is in jupytext "percent" format: ``jupytext --to notebook
plot_tutorial_rock_a_block.py`` makes it a notebook; the gallery page offers one too.)

The physics is the report's (Aslam, Godden & Scalise): a rigid block of height H and
width B stands free on a table; when the table accelerates enough it tips onto a corner
and rocks; every impact on the table keeps a fraction COR of the angular velocity; if the
rotation passes the block angle alpha = arctan(B/H) the block falls over.
"""

# %%
# 1. A block
# ----------
# The report writes sizes as height x width. ``Block`` computes the report's symbols
# (see the nomenclature page): alpha, the slenderness, and p, the frequency parameter.
import numpy as np

import shaketable as st
from shaketable.ground import generators

block = st.Block.parse("30x6in")
print(f"H = {block.height:.3f} m, B = {block.width:.3f} m, alpha = {block.alpha:.4f} rad, "
      f"p = {block.p:.3f} rad/s")
print(f"rocking starts when the table acceleration exceeds g B/H = {block.b / block.h:.2f} g")

# %%
# 2. Rock it freely
# -----------------
# Tilt it to half its block angle and let go, with the COR the report measured for this
# block (0.925, Fig. 3.4). The amplitude decays at each impact and the block comes to rest.
free = st.simulate(block, None, cor=0.925, theta0=0.5 * block.alpha, duration=8.0)
print(free.status, f"rest at t = {free.t_rest:.2f} s, {free.n_impacts} impacts")
free.plot()

# %%
# 3. Shake the table
# ------------------
# A 2 Hz, 0.5 g harmonic table motion (the report's Fig. 3.7), ramped up over one second.
# Accelerations are given in m/s^2: ``0.5 * st.G`` is 0.5 g.
motion = generators.harmonic(2.0, horizontal=0.5 * st.G, duration=10.0, dt=0.0025,
                             ramp=1.0)
result = st.simulate(block, motion, cor=0.925)
print(result.status, f"max |theta|/alpha = {result.max_theta_ratio:.2f}")
result.plot()

# %%
# 4. Change the COR
# -----------------
# The COR is how much of the angular velocity survives an impact. Try a few: which
# ones overturn the block? Is the answer monotone in the COR?
for cor in (0.7, 0.8, 0.85, 0.9, 0.925, 0.95, 0.98):
    run = st.simulate(block, motion, cor=cor)
    when = f" at t = {run.t_overturn:.2f} s" if run.overturned else ""
    print(f"COR {cor:5.3f}: {run.status:>10}{when}, max |theta|/alpha = "
          f"{run.max_theta_ratio:.2f}")

# %%
# 5. Watch it overturn
# --------------------
# theta/alpha against time for a low and a high COR: the block overturns when
# abs(theta)/alpha passes 1 and keeps going (to pi/2, lying on its side).
import matplotlib.pyplot as plt

fig, ax = plt.subplots(figsize=(8, 3.5))
for cor in (0.8, 0.95):
    run = st.simulate(block, motion, cor=cor)
    ax.plot(run.t, run.theta / block.alpha, label=f"COR {cor} ({run.status})")
ax.axhline(1, color="k", lw=0.6, ls="--")
ax.axhline(-1, color="k", lw=0.6, ls="--")
ax.set_xlabel("time [s]")
ax.set_ylabel("theta / alpha [-]")
ax.set_ylim(-3, 3)
ax.legend(frameon=False)
fig.tight_layout()

# %%
# 6. Your turn
# ------------
# * Make the block bigger but just as slender (``"60x12in"``): does it still overturn?
#   (Section 2 of the report: the bigger of two similar blocks is the safer one.)
# * Add a vertical table motion (``generators.harmonic(..., vertical=...)``) or use the
#   recorded Pacoima Dam motion: ``from shaketable.ground import records;
#   records.load("pacoima-dam-s16e")``.
# * Animate a run: ``shaketable animate fig-3-4 --out rocking.gif``.
print(np.round([st.Block.parse(s).p for s in ("30x6in", "60x12in")], 3))
