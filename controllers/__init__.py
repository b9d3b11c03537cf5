"""The built-in PTO controllers of wecss, registered through the ``wecss.controllers`` entry-point group.

The package's folder is ``controllers/``; it imports as ``wecss_controllers`` (pyproject.toml's package-dir
mapping), a name no user folder called ``controllers`` on ``sys.path`` can shadow.

Each follows the protocol of :mod:`wecss.control` (``setup(context)`` once per run, then ``compute(t,
measurement)`` every control period; DESIGN.md, "Controllers"). Built-ins: ``damping`` (linear damping, by
default the device's PTO damping: the M4 paper's 6 N m s/rad), ``spring-damper`` (damping and stiffness, reactive
when the stiffness is negative), ``optimal-damping`` and ``reactive`` (tuned to the scene's sea state on the
exact frequency-domain model) and ``mpc`` (model predictive control maximising the absorbed energy over a
receding horizon). Third-party packages register theirs under the same entry-point group.
"""

from ._damping import LinearDamping as LinearDamping
from ._mpc import MPC as MPC
from ._optimal import OptimalDamping as OptimalDamping
from ._optimal import Reactive as Reactive
from ._spring_damper import SpringDamper as SpringDamper
