"""The attributes of a result Dataset: how the run was made (scene, runner, step, controller, timings, versions),
its sea state's periods and energy flux, and the notes on what was dropped, assumed or found."""

from __future__ import annotations

import datetime as _dt
import json
from typing import Any

import numpy as np

from .. import __version__
from ..compiled import JIT
from ..control import ControlledScene
from ..control.design import PowerBound
from ..waves import energy_flux, energy_period, group_velocity, mean_period
from ._guards import fit_notes, pressure_notes, step_notes, wave_notes
from ._record import Record


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
    bound: PowerBound | None,
    closure: float | None,
) -> dict[str, Any]:
    """The attributes of a run's Dataset. ``motion``: the notes on the record's motion; ``later_notes``: notes
    made while the variables were (the power bound's); ``mean_power``: the mean power per PTO (for the share of
    the power ``bound``); ``closure``: the loads' closure residual where they were recovered."""
    scene = controlled.scene
    n_steps = controlled.n_steps
    report = controlled.controller.report() if controlled.device.ptos else {}
    notes = _notes(controlled, report, motion, record) + later_notes
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
        "controller": scene.controller.name,
        "controller_class": f"{type(controlled.controller).__module__}.{type(controlled.controller).__qualname__}",
        "controller_parameters": json.dumps(scene.controller.parameters),
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
    if bound is not None and mean_power is not None:
        attrs["share_of_power_bound"] = float(np.sum(mean_power) / bound.total)
    return attrs
