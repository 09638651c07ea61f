"""The force terms lunarcap carries, registered in summation order: one line per term.

A term added outside this package registers itself the same way
(:func:`lunarcap.physics.forces.register`) when its module is imported.
"""

from lunarcap.physics.forces.body_pole import BodyPoleJ2
from lunarcap.physics.forces.harmonics import Harmonics
from lunarcap.physics.forces.point import PointMoon
from lunarcap.physics.forces.term import register
from lunarcap.physics.forces.third_body import ThirdBodies
from lunarcap.physics.forces.zonal_j2 import ZonalJ2

register(PointMoon())
register(ZonalJ2())
register(BodyPoleJ2())
register(Harmonics())
register(ThirdBodies())
