# Convergence of DIRT's path tracer: relative MSE against a 64-sample Embree
# reference as samples are added, on the default scene (sweep.png).
import matplotlib.pyplot as plt
import numpy as np

import dirt

scene = dirt.Scene()
ref = dirt.Session(scene, engine="embree", width=64, height=48, seed=1, bounces=2)
ref.add_samples(64)
reference = ref.image()[..., :3]

s = dirt.Session(scene, engine="dirt", width=64, height=48, seed=2, bounces=2)
spp, err = [], []
for n in (1, 1, 2, 4, 8, 16):  # progressive: 1, 2, 4, 8, 16, 32 samples
    s.add_samples(n)
    image = s.image()[..., :3]
    spp.append(s.samples)
    err.append(np.mean((image - reference) ** 2 / (reference ** 2 + 1e-2)))
    print(f"{s.samples:3d} spp  relMSE {err[-1]:.5f}")

plt.loglog(spp, err, "o-", label="DIRT vs Embree (64 spp)")
plt.xlabel("samples per pixel")
plt.ylabel("relative MSE")
plt.legend()
plt.savefig("sweep.png", dpi=100)
