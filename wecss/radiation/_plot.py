"""Plot of a radiation fit: errors per entry against the targets, and fitted against reference kernels."""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

import numpy as np

if TYPE_CHECKING:  # pragma: no cover
    from ._fit import RadiationFit


def plot_fit(fit: RadiationFit, *, max_kernels: int = 6) -> Any:
    """Figure with the fit report (errors of every entry against the targets) and the largest diagonal kernels.

    Returns the matplotlib Figure (``fig.savefig(...)`` to keep it).
    """
    import matplotlib.pyplot as plt

    report = fit.report
    settings = {name: float(report.attrs[name]) for name in ("k0_tol", "rms_tol", "frequency_tol")}
    fig, (ax_err, ax_k) = plt.subplots(1, 2, figsize=(12, 4.5), constrained_layout=True)
    x = np.arange(report.sizes["entry"])
    for name, marker, tol in (
        ("k0_error", "o", settings["k0_tol"]),
        ("rms_error", "s", settings["rms_tol"]),
        ("damping_error", "^", settings["frequency_tol"]),
        ("added_mass_error", "v", settings["frequency_tol"]),
    ):
        ax_err.semilogy(x, np.maximum(report[name].values, 1e-8), marker, ls="none", label=f"{name} (target {tol:g})")
    ax_err.axhline(settings["k0_tol"], color="k", lw=0.8, ls="--")
    ax_err.axhline(settings["frequency_tol"], color="k", lw=0.8, ls=":")
    ax_err.set_xlabel("fitted kernel entry")
    ax_err.set_ylabel("relative error [-]")
    ax_err.set_title(
        f"{report.attrs['method']}: {report.attrs['n_states']} states, margin {report.attrs['passivity_margin']:.2g}"
    )
    ax_err.legend(fontsize=8)
    irf = fit.irf
    peaks = np.max(np.abs(np.diagonal(irf.kernel, axis1=1, axis2=2)), axis=0)
    kernel = fit.model.kernel(irf.time)
    for i in np.argsort(peaks)[::-1][:max_kernels]:
        (line,) = ax_k.plot(irf.time, irf.kernel[:, i, i], lw=1.2, label=irf.dofs[i])
        ax_k.plot(irf.time, kernel[:, i, i], "--", color=line.get_color(), lw=1.0)
    ax_k.set_xlim(0, float(np.max(irf.truncation_time)) * 1.5)
    ax_k.set_xlabel("time [s]")
    ax_k.set_ylabel("K_ii(t) (solid: from B(omega); dashed: fit)")
    ax_k.legend(fontsize=8)
    return fig
