"""The one place that maps a case's description of the body to a :class:`~viscontact.bodies.base.Body`.

A body is described by its material and at most one case key beside it: none for the homogeneous
half-space, ``material.bulk_modulus`` (K [Pa]) for the half-space with nu(t), ``[layer]`` (a
:class:`~viscontact.problem.problem.LayerSettings`) for a layer on a base. :data:`BODIES` maps each key
to the class built from the material and the key's value; a new kind of body adds its key here.
"""
from __future__ import annotations

import dataclasses
from collections.abc import Mapping
from typing import Any

from viscontact.bodies.base import Body
from viscontact.bodies.bulk_elastic import BulkElasticHalfSpace
from viscontact.bodies.half_space import HomogeneousHalfSpace
from viscontact.bodies.layer import LayerOnBase
from viscontact.errors import ParameterError
from viscontact.physics.materials import Material

#: case key describing a body -> the body's class, built as cls(material, value)
BODIES: dict[str, type] = {"bulk_modulus": BulkElasticHalfSpace, "layer": LayerOnBase}
#: the body of a material that no key describes
DEFAULT_BODY = HomogeneousHalfSpace


def body_kind(description: Mapping[str, Any]) -> type:
    """The class of the body that ``description`` (case key -> value, None: not given) describes.

    Raises
    ------
    ParameterError
        Two keys given (``material.bulk_modulus`` with ``[layer]``: a layer's nu is constant).
    """
    given = [key for key, value in description.items() if value is not None]
    if len(given) > 1:
        raise ParameterError("material.bulk_modulus", "not supported with [layer]; give material.poisson_ratio")
    return BODIES[given[0]] if given else DEFAULT_BODY


def body_of(material: Material, body: Body | None = None, **description: Any) -> Body:
    """The body of ``material`` described by the case keys ``description`` (``bulk_modulus=``,
    ``layer=``; None: not given), or ``body`` when given.

    A given ``body`` stands unless ``description`` gives keys that describe another body (a problem
    copied by :func:`dataclasses.replace` with a new ``layer`` or ``bulk_modulus``: the keys are
    newer than the body copied along), and it takes ``material`` (the problem's material is the
    body's)."""
    given = {key: value for key, value in description.items() if value is not None}
    if body is not None and (not given or given == dict(body.description)):
        return body if body.material is material else dataclasses.replace(body, material=material)
    return body_kind(given)(material, *given.values())
