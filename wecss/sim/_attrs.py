"""The attributes of a result Dataset: how the run was made (scene, runner, step, controller, timings, versions),
its sea state's periods and energy flux, and the notes on what was dropped, assumed or found."""

from __future__ import annotations

import datetime as _dt
import json
from typing import Any

import numpy as np

from .. import __version__
from ..compiled import JIT, SHIPPED_DATA_DIR, device_spec_path, recorded_inputs
from ..control import ControlledScene, controller_attrs
from ..provenance import INPUTS_ATTR, SPEC_ATTR, array_digest, input_records
from ..waves import energy_flux, energy_period, group_velocity, mean_period
from ._bound_window import SHARE_TOLERANCE
from ._guards import fit_notes, pressure_notes, step_notes, wave_notes
from ._injection import injection_notes
from ._record import Record
from ._watchdog import unenforced


def sea_state_attrs(controlled: ControlledScene) -> dict[str, Any]:
    """Energy period, mean period and energy flux of the scene's sea state (for the capture width ratio)."""
    sea = controlled.scene.sea
    hydro = controlled.hydro
    rho, g, depth = hydro.rho, hydro.g, hydro.water_depth
    out: dict[str, Any] = {"sea_kind": sea.kind}
    spectrum = controlled.spectrum
    if spectrum is not None:
        out["energy_period"] = energy_period(spectrum)
        out["mean_period"] = mean_period(spectrum)
        out["wave_energy_flux"] = energy_flux(spectrum, depth, rho, g)
        out["wave_energy_flux_source"] = "theoretical spectrum"
        if sea.period is not None:
            out["peak_period"] = float(sea.period)
        out["significant_wave_height"] = 4 * np.sqrt(spectrum.moment(0))
    elif controlled.waves is not None:
        w = controlled.waves
        variance = np.abs(w.amplitude) ** 2 / 2
        out["energy_period"] = float(2 * np.pi * np.sum(variance / w.omega) / np.sum(variance))
        out["mean_period"] = float(2 * np.pi * np.sum(variance) / np.sum(variance * w.omega))
        out["wave_energy_flux"] = float(rho * g * np.sum(variance * group_velocity(w.omega, depth, g)))
        out["wave_energy_flux_source"] = "simulated wave components"
        out["significant_wave_height"] = float(4 * np.sqrt(np.sum(variance)))
        if sea.period is not None:
            out["peak_period"] = float(sea.period)
    return out


FIT_ATTR = "radiation_fit_sha256"
"""The result attribute holding the SHA-256 of the radiation fit's matrices (:func:`fit_digest`)."""


def fit_digest(controlled: ControlledScene) -> str:
    """The SHA-256 of the state-space radiation fit's matrices A, B, C ("" without a fit)."""
    fit = controlled.radiation_fit
    return "" if fit is None else array_digest(fit.model.A, fit.model.B, fit.model.C)


def input_attrs(controlled: ControlledScene) -> dict[str, str]:
    """The run's input files with their SHA-256 (``input_files``, JSON; ``wecss.provenance``) and the device
    spec's text as read (``device_spec``)."""
    spec = device_spec_path(controlled.scene)
    return {
        INPUTS_ATTR: json.dumps(input_records(recorded_inputs(controlled.scene), SHIPPED_DATA_DIR)),
        SPEC_ATTR: spec.read_text(encoding="utf-8-sig") if spec is not None else "",
    }


def _notes(controlled: ControlledScene, report: dict[str, Any], motion: list[str], record: Record) -> list[str]:
    notes = [*controlled.notes, *fit_notes(controlled), *step_notes(controlled), *wave_notes(controlled), *motion]
    notes += pressure_notes(controlled, record.pressure_flags)
    if controlled.device.ptos and not controlled.linear_controller:
        steps = controlled.scene.control_steps
        notes.append(
            "controller force held constant over each step (zero-order hold at the simulation step)"
            if steps == 1
            else f"controller called every {steps} steps ({steps * controlled.dt:.6g} s), its force held in between"
        )
        unwatched = unenforced(controlled.scene.controller.time_limit)
        if unwatched is not None:
            notes.append(unwatched)
    if controlled.controller_given:
        choice = controlled.scene.controller
        notes.append(
            f"the controller given to simulate ({type(controlled.controller).__name__}) ran; the scene's controller "
            f"section ({choice.name!r}, {dict(choice.parameters)}) was not used"
        )
    if report:
        notes.append(
            "controller: "
            + ", ".join(f"{k} = {v:.4g}" if isinstance(v, float) else f"{k} = {v}" for k, v in report.items())
        )
    return notes


def result_attrs(
    controlled: ControlledScene,
    record: Record,
    motion: list[str],
    *,
    later_notes: list[str],
    mean_power: np.ndarray | None,
    bound: tuple[np.ndarray | None, np.ndarray] | None,
    closure: float | None,
) -> dict[str, Any]:
    """The attributes of a run's Dataset. ``motion``: the notes on the record's motion; ``later_notes``: notes
    made while the variables were (the power bound's); ``mean_power``: the mean power per PTO [W];
    ``bound``: the power bound per PTO over the run's window (None where it could not be had) and its spectral
    expectation [W], for the shares;
    ``closure``: the loads' closure residual where they were recovered."""
    scene = controlled.scene
    n_steps = controlled.n_steps
    report = controlled.controller.report() if controlled.device.ptos else {}
    notes = _notes(controlled, report, motion, record) + later_notes + injection_notes(controlled, mean_power)
    attrs: dict[str, Any] = {
        "title": f"wecss simulation of {controlled.device.name}",
        "Conventions": "CF-1.10",
        "history": f"{_dt.datetime.now(_dt.UTC).isoformat(timespec='seconds')} wecss {__version__}: simulate "
        f"({scene.runner.name})",
        "wecss_version": __version__,
        "scene": scene.to_json(),
        "device": controlled.device.name,
        "solver": scene.runner.name,
        "time_step": controlled.dt,
        "n_steps": n_steps,
        "saved_every": scene.outputs.every,
        "statistics_window": scene.outputs.window,
        "radiation": str(controlled.radiation_summary),
        **controller_attrs(controlled.controller, given=controlled.controller_given),
        "controller_linear_gains_in_equations": int(controlled.linear_controller),
        "numba": int(JIT),
        "run_time_s": record.run_time,
        "steps_per_second": n_steps / record.run_time if record.run_time > 0 else float("inf"),
        "seed": scene.sea.seed,
        "notes": "; ".join(notes) or "none",
        "rho": controlled.hydro.rho,
        "g": controlled.hydro.g,
        "moorings": json.dumps([m.to_dict() for m in controlled.device.moorings])
        if controlled.device.moorings
        else "none",
    }
    attrs.update(input_attrs(controlled))
    attrs.update({f"controller_{k}": v for k, v in report.items()})
    attrs.update(record.solver)  # each run describes its own solver (and its radiation model where it has its own)
    attrs.update(sea_state_attrs(controlled))
    if closure is not None:
        attrs["loads_closure_residual"] = closure
    if controlled.radiation_fit is not None:  # the state-space fit's passivity and stability, where a user chose it
        fit = controlled.radiation_fit.report.attrs
        attrs["radiation_fit_passivity_margin"] = float(fit["passivity_margin"])
        attrs["radiation_fit_passive"] = int(fit.get("passive", float(fit["passivity_margin"]) >= 0))
        attrs["radiation_fit_stable"] = int(fit["stable"])
        attrs["radiation_fit_repair"] = str(fit["repair"])
        attrs[FIT_ATTR] = fit_digest(controlled)
    if bound is not None and mean_power is not None:
        attrs.update(bound_shares(np.sum(mean_power), *bound))
        notes = bound_notes(attrs)
        if notes:
            attrs["notes"] = "; ".join(n for n in (attrs["notes"], *notes) if n != "none")
    return attrs


def bound_shares(total: float, window: np.ndarray | None, spectral: np.ndarray) -> dict[str, float]:
    """The run's total mean power ``total`` [W] as shares of the complex-conjugate bound over its own record and
    window (``share_of_power_bound``, with the tolerance above 1 that it may reach without a note; left out with
    ``window`` None, where that bound could not be had) and of its spectral expectation
    (``share_of_power_bound_spectral``)."""
    shares = {"share_of_power_bound_spectral": float(total / np.sum(spectral))}
    if window is not None:
        shares["share_of_power_bound"] = float(total / np.sum(window))
        shares["share_of_power_bound_tolerance"] = SHARE_TOLERANCE
    return shares


def bound_notes(attrs: dict[str, Any]) -> list[str]:
    """A note when the run's share of the bound on its own record and window exceeds 1 beyond its tolerance."""
    share, tolerance = attrs.get("share_of_power_bound"), attrs.get("share_of_power_bound_tolerance")
    if share is None or tolerance is None or not share > 1 + tolerance:
        return []
    return [
        f"mean absorbed power is {share:.4g} times the complex-conjugate bound on the same record and window (more "
        f"than 1 + {tolerance:g}): the linear model's bound does not hold for this run (nonlinear forces, a time "
        "step too long for the power, or energy stored in the device at the window's ends)"
    ]
