import numpy as np
import rayint

# A case file, as `rayint eval` reads it: the report is the CLI's JSON, as a dict.
report = rayint.evaluate("cases/narrow-pulse.json", methods=["exact", "nerf:n=64", "pl_nerf:n=64"])
for ray in report["cases"][0]["rays"][:3]:
    print("ray", ray["index"], {m: f"{max(r['rel_error']):.2g}" for m, r in ray["methods"].items()})

# Your own samples as NumPy arrays: linear pieces, density rho and colour kappa from the exit
# (eye) end to the far end; exact emission and transmittance of each piece, GIL released.
rho_exit, rho_far = np.array([1.0, 0.0, 4.0]), np.array([3.0, 2.0, 4.0])
kappa_exit, kappa_far = np.array([0.5, 1.0, 0.2]), np.array([0.5, 0.0, 0.9])
length = np.array([1.0, 0.25, 2.0])
emission, transmittance = rayint.exact_pieces(rho_exit, rho_far, kappa_exit, kappa_far, length)
print(emission, transmittance)
