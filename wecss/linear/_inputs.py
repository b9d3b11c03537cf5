"""The linear model's input vector rebuilt from a result: u(t) = [F_exc, f_pto] in the order of
:func:`wecss.linear.linearize`'s inputs, for identifying models from runs or checking the linear plant against the
nonlinear simulator."""

from __future__ import annotations

import numpy as np
import xarray as xr

from ..compiled import CompiledScene, pto_control_force
from ..hydro import dof_kind
from ._model import LinearModel, linearize


def linear_inputs(result: xr.Dataset, compiled: CompiledScene, model: LinearModel | None = None) -> xr.DataArray:
    """The inputs u(t) of the linear model that drive it as the run ``result`` was driven.

    Inputs, in the order of ``model.state_space.input_labels`` (``excitation__<body>__<Dof>`` per hydro DOF, then
    ``force__<pto>`` per PTO):

    - the wave excitation on every hydro DOF, world axes [N, N m], from ``excitation_force`` and
      ``excitation_moment`` (the result needs the ``excitation`` outputs; the start ramp is in them);
    - per PTO, the part of the PTO force the model does not hold [N or N m]: the result's total ``pto_force`` /
      ``pto_torque`` f plus what the model's equations already give, f_pto = f + (k_s + k) x + c x_dot + (k_0 - k) x0,
      with x the stroke from rest and x_dot its rate (``pto_displacement`` / ``pto_angle`` and rates), k_s the
      device springs, c and k the PTO gains folded into ``model``, k_0 those of the scene (whose static force is
      balanced in the equilibrium) and x0 the equilibrium stroke. For the scene's own model and a controller with
      linear gains this is zero; for the open plant (``model.with_pto_gains()``) it is the controller's force.

    Feeding u to ``model`` from rest at the equilibrium reproduces a linear run of the same scene (exactly, for the
    model the run used and ``outputs.every = 1``) and approximates a nonlinear one to the linearisation error.
    Values are those at the result's saved steps; a controller's held force is recorded at the end of the step
    over which it acted, and end-stop forces are not in ``pto_force``.

    Parameters
    ----------
    result : Dataset
        A result of ``compiled``'s scene with the ``excitation`` outputs (and ``pto`` for a device with PTOs).
    compiled : CompiledScene
        The scene the result was run from (``compile_scene(Scene.from_json(result.attrs["scene"]))``).
    model : LinearModel, optional
        The linear model to drive (default: ``linearize(compiled)``, which needs state-space radiation only for
        its ``state_space``).

    Returns
    -------
    DataArray
        Dims (time, input), the input labels as the ``input`` coordinate.

    Raises
    ------
    ValueError
        If the result lacks the variables needed, or its DOFs or PTOs are not the scene's.
    TypeError
        If ``compiled`` is not a CompiledScene.
    """
    if not isinstance(compiled, CompiledScene):
        raise TypeError(f"linear_inputs takes the result's CompiledScene; got {type(compiled).__name__}")
    model = model or linearize(compiled)
    dofs = list(compiled.hydro.dofs)
    ptos = [p.name for p in compiled.device.ptos]
    needed = [_excitation_variable(result, d)[0] for d in dofs]
    if ptos:
        needed.append("pto_power")
    missing = sorted({name for name in needed if name not in result})
    if missing or "time" not in result.dims:
        raise ValueError(
            f"the result lacks {', '.join(missing) or 'time series'}: run the scene with outputs.variables "
            "including 'excitation' and 'pto' (not statistics_only)"
        )
    columns = []
    for dof in dofs:
        name, dim = _excitation_variable(result, dof)
        if dof not in result[dim].values:
            raise ValueError(f"hydro DOF {dof!r} of the scene is not in the result's {dim}: another scene's result?")
        columns.append(result[name].sel({dim: dof}).values)
    if ptos:
        if [str(p) for p in result.pto.values] != ptos:
            raise ValueError(f"the result's PTOs {list(result.pto.values)} are not the scene's {ptos}")
        stroke = _by_kind(result, "pto_angle", "pto_displacement")
        rate = _by_kind(result, "pto_angular_velocity", "pto_velocity")
        force = _by_kind(result, "pto_torque", "pto_force")
        p = compiled.plant
        folded = model.pto_stiffness
        # the PTO input is the force less what the model itself applies: the device spring and the folded gains
        folded_force = pto_control_force(0.0, model.pto_damping, folded, stroke, rate)
        columns += list(
            (force + p.pto_spring * stroke - folded_force + (p.pto_stiffness - folded) * model.pto_stroke).T
        )
    labels = [*(f"excitation__{d}" for d in dofs), *(f"force__{n}" for n in ptos)]
    return xr.DataArray(
        np.stack(columns, axis=1),
        dims=("time", "input"),
        coords={"time": result.time.values, "input": labels},
        name="linear_input",
        attrs={
            "long_name": "input of the linear model: excitation per hydro DOF, then force per PTO",
            "units": "N, N m",
        },
    )


def _excitation_variable(result: xr.Dataset, dof: str) -> tuple[str, str]:
    """The result's variable and dimension holding the excitation on hydro DOF ``dof``: by its kind (a generalised
    mode's on ``hydro_dof_generalised`` when the result has that dimension, else with the translations)."""
    kind = dof_kind(dof)
    if kind == "angular":
        return "excitation_moment", "hydro_dof_angular"
    if kind == "generalised" and "hydro_dof_generalised" in result.dims:
        return "excitation_generalised_force", "hydro_dof_generalised"
    return "excitation_force", "hydro_dof_linear"


def _by_kind(result: xr.Dataset, rotary: str, linear: str) -> np.ndarray:
    """(n_t, n_pto) values of a PTO quantity whose rotary and linear PTOs are in two variables (NaN for the
    other kind)."""
    parts = [result[name].transpose("time", "pto").values for name in (rotary, linear) if name in result]
    if not parts:
        raise ValueError(f"the result lacks {rotary} and {linear}: run the scene with the 'pto' outputs")
    out = parts[0].copy()
    for part in parts[1:]:
        out = np.where(np.isnan(out), part, out)
    return out
