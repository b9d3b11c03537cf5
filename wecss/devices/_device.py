"""``Device``: a multibody model with its PTOs, hydrodynamic database and stated assumptions."""

from __future__ import annotations

import inspect
from collections.abc import Callable, Mapping
from dataclasses import dataclass, field, replace
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np
import xarray as xr
from scipy.linalg import eig

from ..constants import GRAVITY
from ..hydro import HydroData, is_wecss_database, read_bemio, read_capytaine, read_wamit
from ..hydro import load as load_hydro
from ..multibody import (
    ActuatorPTO,
    Body,
    BodyDrag,
    Dynamics,
    HydroCoupling,
    JointPTO,
    Mooring,
    MorisonElement,
    Multibody,
    StaticModel,
)
from ..structure import Frame
from ._flexible import (
    BodyMass,
    Flexible,
    FlexibleBody,
    body_frame,
    body_points,
    check_structural_mass,
    flexible_body,
    read_masses,
)
from ._members import Member, read_members
from ._meshes import BodyMesh, read_meshes
from ._spec import DeviceSpecError, build_model, build_moorings, build_viscous, hydro_source, read_spec
from ._structural_modes import structural_modes

if TYPE_CHECKING:  # pragma: no cover
    from ..hydro.mesh import SurfaceMesh


@dataclass(frozen=True, eq=False)
class Device:
    """A wave energy converter: bodies, joints, PTOs, the hydrodynamic database it uses and its assumptions.

    Build it with :meth:`from_spec` or :func:`wecss.devices.load`.

    Attributes
    ----------
    name, description : str
    model : Multibody
    ptos : tuple of JointPTO or ActuatorPTO
    hydro_source : str or None
        Shipped database name or path to a database file (netCDF, WAMIT .out, Capytaine .nc).
    assumptions : mapping of str to str
        Every number that is not published, with its reason.
    spec : dict
        The spec it was built from (for round trips into result attributes).
    members : tuple of Member
        Beam members for stress recovery (empty when the spec declares none).
    moorings : tuple of Mooring
        Linear moorings (empty when the spec declares none).
    drag : tuple of BodyDrag
        Viscous drag and linear damping on bodies' DOFs (act when a scene asks for ``hydrodynamics.drag``).
    morison : tuple of MorisonElement
        Morison cylinders (the same).
    meshes : tuple of BodyMesh
        Bodies' surface meshes (``[[meshes]]``) for the body-exact hydrostatic and Froude-Krylov forces
        (``wecss.devices._meshes``); :meth:`surface_mesh` builds one.
    hydro_options : mapping
        Keyword arguments of the reader of the ``hydro`` file (the spec's ``[hydro_options]``).
    flexible : mapping of str to Flexible
        The flexible bodies and their ``flexible`` tables (empty when every body is rigid).
    masses : tuple of BodyMass
        Lumped masses of the flexible bodies' structural models (the spec's ``[[masses]]``).
    """

    name: str
    description: str
    model: Multibody
    ptos: tuple[JointPTO | ActuatorPTO, ...]
    hydro_source: str | None
    assumptions: Mapping[str, str]
    spec: Mapping[str, Any] = field(repr=False)
    members: tuple[Member, ...] = ()
    moorings: tuple[Mooring, ...] = ()
    hydro_options: Mapping[str, Any] = field(default_factory=dict)
    drag: tuple[BodyDrag, ...] = ()
    morison: tuple[MorisonElement, ...] = ()
    meshes: tuple[BodyMesh, ...] = ()
    flexible: Mapping[str, Flexible] = field(default_factory=dict)
    masses: tuple[BodyMass, ...] = ()

    @classmethod
    def from_spec(cls, source: str | Path | Mapping[str, Any]) -> Device:
        """Build a device from a TOML spec file or a dict with the same keys (see ``wecss.devices._spec``).

        Raises
        ------
        DeviceSpecError
            On a malformed spec (the message says where).
        FileNotFoundError
            If the spec file does not exist.
        """
        spec, folder = read_spec(source)
        try:
            return cls._from_read_spec(spec, folder)
        except DeviceSpecError as err:
            if folder is None or str(err).startswith(str(source)):
                raise
            raise DeviceSpecError(f"{source}: {err}") from None

    @classmethod
    def _from_read_spec(cls, spec: dict[str, Any], folder: Path | None) -> Device:
        """The device of a spec read by ``read_spec`` (``folder``: its file's folder, None for a dict)."""
        model, ptos = build_model(spec)
        hydro = hydro_source(spec, folder)
        assumptions = {str(k): str(v) for k, v in spec.get("assumptions", {}).items()}
        try:
            members = read_members(spec["name"], list(spec.get("members", [])), list(model.body_names))
        except ValueError as err:
            raise DeviceSpecError(str(err)) from None
        moorings = build_moorings(spec, model)
        drag, morison = build_viscous(spec, model)
        try:
            meshes = read_meshes(spec, folder, model)
        except ValueError as err:
            raise DeviceSpecError(str(err)) from None
        options = spec.get("hydro_options", {})
        if not isinstance(options, Mapping):
            raise DeviceSpecError(f"device {spec['name']!r}: hydro_options must be a table; got {options!r}")
        flexible, masses = _read_flexible(spec, model, ptos, members)
        return cls(
            spec["name"], spec.get("description", ""), model, ptos, hydro, assumptions, spec, members, moorings,
            dict(options), drag, morison, meshes, flexible, masses,
        )  # fmt: skip

    def member(self, name: str) -> Member:
        """The beam member of that name.

        Raises
        ------
        KeyError
            If there is none (the message lists the members).
        """
        for m in self.members:
            if m.name == name:
                return m
        raise KeyError(f"device {self.name!r} has no member {name!r}; members: {[m.name for m in self.members]}")

    def surface_mesh(self, body: str) -> SurfaceMesh:
        """The surface mesh of ``body`` in its body frame (from its centre of mass; see ``wecss.devices._meshes``).

        Raises
        ------
        KeyError
            If the spec declares no mesh for the body (the message lists those it declares).
        """
        for m in self.meshes:
            if m.body == body:
                return m.surface(self.model)
        raise KeyError(
            f"device {self.name!r} declares no mesh of body {body!r} ([[meshes]]); meshes: "
            f"{[m.body for m in self.meshes] or 'none'}"
        )

    # --- structure ---------------------------------------------------------------------------------
    def _flexible_spec(self, body: str) -> Flexible:
        if body not in self.flexible:
            known = sorted(self.flexible) or "none"
            raise ValueError(
                f"device {self.name!r}: body {body!r} is not flexible (flexible bodies: {known}); give it a "
                "flexible = {...} table in the spec"
            )
        return self.flexible[body]

    def structure(self, body: str) -> Frame:
        """The frame of a flexible body's members and lumped masses with its named points (``clamp``,
        ``joint:<name>``, ``pto:<name>``; see ``wecss.devices._flexible``).

        Raises
        ------
        ValueError
            If the body is not flexible.
        """
        return body_frame(self.model, self.ptos, self.members, self.masses, body, self._flexible_spec(body))

    def flexible_body(self, body: str) -> FlexibleBody:
        """The reduced model of a flexible body: Craig-Bampton basis with inertia-relief vectors, invariants about
        its centre of mass, stress modes (see :class:`FlexibleBody`).

        Raises
        ------
        ValueError
            If the body is not flexible.
        """
        return flexible_body(self.model, self.ptos, self.members, self.masses, body, self._flexible_spec(body))

    def _refuse_elastic(self, what: str) -> None:
        """Refuse a rigid-model method of a device whose elastic bodies are not in its model (it would run them
        rigid)."""
        if self.elastic_bodies and not self.model.elastic_bodies:
            raise ValueError(
                f"device {self.name!r}: Device.{what} would use the rigid model, and bodies "
                f"{list(self.elastic_bodies)} have flexible.dynamics = 'elastic'; use Device.with_elastic_model(), "
                "or dynamics = 'frozen'"
            )

    def with_elastic_model(self) -> Device:
        """This device with :meth:`elastic_model` as its :attr:`model` (its elastic bodies' modes in the equations
        of motion; its coupling, statics and dynamics then carry them); itself when it has no elastic body or its
        model already carries them."""
        if not self.elastic_bodies or self.model.elastic_bodies:
            return self
        return replace(self, model=self.elastic_model())

    @property
    def elastic_bodies(self) -> tuple[str, ...]:
        """The flexible bodies whose modes move in the equations of motion (``flexible.dynamics = "elastic"``)."""
        return tuple(name for name, f in self.flexible.items() if f.dynamics == "elastic")

    def elastic_model(self) -> Multibody:
        """The device's tree with its elastic bodies (``flexible.dynamics = "elastic"``) in a floating frame: each
        such body takes its structural model's mass, centre of mass and inertia (the structure carries the body's
        mass, to ``MASS_TOLERANCE``) and its modal coordinates (``<body>__flex1``, ...) join the generalised
        coordinates after the joints'; its children ride on its nodes (``FlexibleBody.elastic_body``). Without
        elastic bodies, or when :attr:`model` already carries them, it is :attr:`model` itself.

        Raises
        ------
        ValueError
            If an elastic body is wetted (it has hydrodynamics or a mesh): floats stay rigid children of flexible
            members; the wetted modes of a flexible body are not modelled.
        """
        if not self.elastic_bodies or self.model.elastic_bodies:
            return self.model
        bodies = list(self.model.bodies)
        for name in self.elastic_bodies:
            k = self.model.body_names.index(name)
            body = bodies[k]
            meshed = [m.body for m in self.meshes]
            if body.hydro_body is not None or name in meshed:
                raise ValueError(
                    f"device {self.name!r}: body {name!r} has flexible.dynamics = 'elastic' and is wetted (hydro body "
                    f"{body.hydro_body!r}{', a mesh' if name in meshed else ''}); the wetted modes of a flexible body "
                    "are not modelled: make the float a rigid child of the flexible member, or use dynamics = "
                    "'frozen'"
                )
            elastic = self.flexible_body(name).elastic_body()
            inv = elastic.invariants
            bodies[k] = Body(name, inv.mass, inv.inertia, inv.origin, None, elastic=elastic)
        return Multibody(bodies, self.model.joints)

    def structural_modes(self, **options: Any) -> xr.Dataset:
        """Natural modes of the device with its flexible bodies, in water or in air:
        :func:`wecss.devices.structural_modes` (its keywords: ``water``, ``hydro``, ``model``, ``n_modes``,
        ``plane_normal``, ``pto_damping``, ``iterations``)."""
        return structural_modes(self, **options)

    # --- hydrodynamics ----------------------------------------------------------------------------
    def hydro(self, source: str | Path | HydroData | None = None) -> HydroData:
        """The device's hydrodynamic database (``source`` overrides the spec's: a HydroData, name or path).

        A BEM output file is read with the spec's ``[hydro_options]`` (keyword arguments of its reader:
        ``HydroData.from_capytaine`` for a Capytaine ``.nc``, ``from_wamit`` for ``.out``, ``from_bemio`` for
        ``.h5``). A ``.nc`` file is a wecss database when it carries the schema's ``rho`` and ``g`` attributes,
        else Capytaine output (always, when options are given).

        Raises
        ------
        ValueError
            If neither the spec nor ``source`` names a database; if ``hydro_options`` are given for a shipped
            database (not a BEM output file), or name keywords the reader does not take.
        FileNotFoundError
            If the file does not exist.
        HydroDataError
            If the file is not a readable database (the message names the file and what is wrong).
        """
        src = self.hydro_source if source is None else source
        options = dict(self.hydro_options)
        if isinstance(src, HydroData):  # already read
            return src
        if src is None:
            raise ValueError(f"device {self.name!r} names no hydrodynamic database; pass one (HydroData, name or path)")
        path = Path(src)
        if path.suffix in (".out", ".nc", ".h5") and not path.is_file():
            raise FileNotFoundError(f"device {self.name!r}: no hydrodynamic database at {str(path)!r}")
        if path.suffix in (".out", ".h5"):
            return self._read(path, options)
        if path.suffix == ".nc":
            if options or not is_wecss_database(path):
                return self._read(path, options)
            return HydroData.from_netcdf(path)
        self._check_no_options(options, f"the shipped database {str(src)!r}")
        return load_hydro(str(src))

    def _check_no_options(self, options: Mapping[str, Any], what: str) -> None:
        if options:
            raise ValueError(
                f"device {self.name!r}: hydro_options {sorted(options)} apply to a BEM output file (Capytaine .nc, "
                f"WAMIT .out, BEMIO .h5); the database is {what}"
            )

    def _read(self, path: Path, options: Mapping[str, Any]) -> HydroData:
        """The BEM output file at ``path`` read by its reader (from its suffix) with ``options``, checked against
        the reader's keywords."""
        readers: dict[str, tuple[Callable[..., HydroData], Callable[..., Any]]] = {
            ".nc": (HydroData.from_capytaine, read_capytaine),
            ".out": (HydroData.from_wamit, read_wamit),
            ".h5": (HydroData.from_bemio, read_bemio),
        }
        reader, inner = readers[path.suffix]
        keywords = {n for n in inspect.signature(inner).parameters if n not in ("source", "path")}
        accepted = sorted({"repair", *keywords})
        unknown = sorted(set(options) - set(accepted))
        if unknown:
            raise DeviceSpecError(
                f"device {self.name!r}: hydro_options {unknown} are not keywords of the reader of {path.name} "
                f"(HydroData.{reader.__name__}); accepted: {', '.join(accepted)}"
            )
        return reader(path, **options)

    def coupling(self, hydro: str | Path | HydroData | None = None) -> HydroCoupling:
        """The hydrodynamic database mapped onto the model's Cartesian coordinates (at the bodies' centres of mass),
        with the device's moorings.

        Raises
        ------
        ValueError
            If the model's bodies do not match the database's, or a mooring holds a DOF the database has no data
            for.
        """
        self._refuse_elastic("coupling")
        return self._coupling(hydro)

    def _coupling(self, hydro: str | Path | HydroData | None) -> HydroCoupling:
        return HydroCoupling.from_hydro(self.model, self.hydro(hydro), self.moorings)

    def rigid_statics(self, hydro: str | Path | HydroData | None = None, *, with_hydro: bool = True) -> StaticModel:
        """The statics of the rigid model (:attr:`model`), flexible bodies frozen whatever their ``dynamics``: the
        equilibrium the structural modal analysis linearises about."""
        coupling = self._coupling(hydro) if with_hydro else None
        g = coupling.hydro.g if coupling is not None else GRAVITY
        return StaticModel(self.model, g, coupling, self.ptos)

    def statics(self, hydro: str | Path | HydroData | None = None, *, with_hydro: bool = True) -> StaticModel:
        """Gravity, buoyancy, hydrostatics and PTO springs at rest."""
        self._refuse_elastic("statics")
        return self.rigid_statics(hydro, with_hydro=with_hydro)

    def dynamics(self, hydro: str | Path | HydroData | None = None, *, with_hydro: bool = True) -> Dynamics:
        """MFM dynamics with the infinite-frequency added mass (when ``with_hydro``)."""
        self._refuse_elastic("dynamics")
        added = self.coupling(hydro).added_mass_inf if with_hydro else None
        return Dynamics(self.model, added)

    def natural_periods(self, hydro: str | Path | HydroData | None = None) -> dict[str, Any]:
        """Undamped natural periods about the static equilibrium, with infinite-frequency added mass.

        Returns
        -------
        dict
            ``equilibrium`` (q), ``periods`` [s] sorted (inf for modes without stiffness) and ``modes``
            (columns normalised to the largest entry, rows ``model.velocity_names``).

        Raises
        ------
        ValueError
            If the device has no degree of freedom (every joint fixed or welded).
        """
        if self.model.nv == 0:
            raise ValueError(f"device {self.name!r} has no degree of freedom (every joint fixed or welded)")
        statics = self.statics(hydro)
        q = statics.equilibrium()
        mass = self.dynamics(hydro).terms(q, np.zeros(self.model.nv)).mass
        stiffness = statics.stiffness(q)
        values, vectors = eig(stiffness, mass)
        omega2 = np.real(values)
        tiny = 1e-9 * max(1.0, float(np.max(np.abs(omega2))))
        periods = np.full(omega2.shape, np.inf)
        stiff = omega2 > tiny
        periods[stiff] = 2 * np.pi / np.sqrt(omega2[stiff])
        vectors = np.real(vectors)
        vectors = vectors / np.max(np.abs(vectors), axis=0, keepdims=True)
        order = np.argsort(-periods, kind="stable")
        return {"equilibrium": q, "periods": periods[order], "modes": vectors[:, order]}

    def info(self, hydro: str | Path | HydroData | None = None) -> str:
        """Bodies, joints, generalised coordinates, masses, PTOs and (when hydro data load) natural periods."""
        m = self.model
        lines = [f"device {self.name}: {self.description}".rstrip(": "), "", "bodies:"]
        for b in m.bodies:
            lines.append(
                f"  {b.name:10s} mass {b.mass:10.4g} kg  centre of mass {np.round(b.center_of_mass, 4).tolist()} m  "
                f"inertia diag {np.round(np.diag(b.inertia), 4).tolist()} kg m^2  hydro {b.hydro_body or '-'}"
            )
            if b.name in self.flexible:
                f = self.flexible[b.name]
                on_body = [m.name for m in self.members if m.body == b.name]
                lines.append(
                    f"  {'':10s} flexible: members {', '.join(on_body)}; {f.elements} elements per member, {f.theory}, "
                    f"{f.modes} fixed-interface modes, damping ratio {f.damping_ratio:g} (`wecss modes` for its modes)"
                )
            if b.modes.n:
                lines.append(
                    f"  {'':10s} generalised modes {', '.join(b.modes.names)}: mass diag "
                    f"{np.round(np.diag(b.modes.mass), 4).tolist()} kg m^2, stiffness diag "
                    f"{np.round(np.diag(b.modes.stiffness), 4).tolist()} N m"
                )
        lines.append("joints:")
        for j in m.ordered_joints:
            extra = ""
            if j.axis is not None:
                extra += f" axis {np.round(j.axis, 4).tolist()}"
            if j.point is not None:
                extra += f" point {np.round(j.point, 4).tolist()} m"
            lines.append(f"  {j.name:10s} {j.kind:9s} {j.parent or 'ground'} -> {j.child}{extra}")
        lines.append(f"generalised coordinates ({m.nv} DOF): {', '.join(m.velocity_names)}")
        lines.append("PTOs:")
        for p in self.ptos:
            where = (
                f"joint {p.joint}" if isinstance(p, JointPTO) else f"{p.body_a or 'ground'} -> {p.body_b or 'ground'}"
            )
            lines.append(f"  {p.name:10s} {where}: damping {p.damping:g}, stiffness {p.stiffness:g}")
        if self.moorings:
            lines.append("moorings:")
            for mooring in self.moorings:
                parts = [f"{d} {v:g}" for d, v in mooring.stiffness.items()]
                parts += [f"{d} damping {v:g}" for d, v in mooring.damping.items()]
                lines.append(f"  {mooring.body:10s} {', '.join(parts)} [SI]")
        try:
            result = self.natural_periods(hydro)
        except (ValueError, FileNotFoundError) as err:
            lines.append(f"natural periods: not available ({err})")
        else:
            lines.append(
                "undamped natural periods with infinite-frequency added mass [s] and the largest mode entries:"
            )
            names = m.velocity_names
            for period, mode in zip(result["periods"], result["modes"].T, strict=True):
                top = np.argsort(np.abs(mode))[::-1][:3]
                shape = ", ".join(f"{names[k]} {mode[k]:+.2f}" for k in top if abs(mode[k]) > 0.05)
                text = "inf (no stiffness)" if np.isinf(period) else f"{period:8.3f}"
                lines.append(f"  {text:>18s}  {shape}")
        if self.assumptions:
            lines.append("assumptions:")
            lines.extend(f"  {k}: {v}" for k, v in self.assumptions.items())
        return "\n".join(lines)


def _read_flexible(
    spec: Mapping[str, Any], model: Multibody, ptos: tuple[JointPTO | ActuatorPTO, ...], members: tuple[Member, ...]
) -> tuple[dict[str, Flexible], tuple[BodyMass, ...]]:
    """The spec's flexible tables and lumped masses, checked: members with materials, a clamp, the body's mass.

    Raises
    ------
    DeviceSpecError
        Naming the body, mass or member, the field, the value and what is accepted.
    """
    name = spec["name"]
    flexible: dict[str, Flexible] = {}
    for k, entry in enumerate(spec["bodies"]):
        if "flexible" in entry:
            where = f"device {name!r}, bodies[{k}] ({entry['name']!r})"
            try:
                flexible[entry["name"]] = Flexible.from_spec(where, entry["flexible"])
            except ValueError as err:
                raise DeviceSpecError(str(err)) from None
    entries = spec.get("masses", [])
    if not isinstance(entries, list):
        raise DeviceSpecError(f"device {name!r}: masses must be a list of tables ([[masses]])")
    try:
        masses = read_masses(name, entries, list(flexible))
        for body, table in flexible.items():
            body_points(model, ptos, body, table)
            check_structural_mass(model, members, masses, body)
    except ValueError as err:
        raise DeviceSpecError(f"device {name!r}: {err}") from None
    return flexible, masses


__all__ = ["Device", "DeviceSpecError"]
