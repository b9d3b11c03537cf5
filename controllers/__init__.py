"""PTO controllers for wecss, registered through the ``wecss.controllers`` entry-point group.

A controller is set up once with ``setup(model, dt)`` and then asked for the PTO forces every control step with
``compute(t, measurement)`` (DESIGN.md, "Controllers"). Built-ins: ``damping`` (linear damping, with the M4
paper's 6 N m s/rad as its default). Third-party packages register theirs under the same entry-point group.
"""

from ._base import Controller as Controller
from ._base import Measurement as Measurement
from ._base import available as available
from ._base import create as create
from ._damping import LinearDamping as LinearDamping
