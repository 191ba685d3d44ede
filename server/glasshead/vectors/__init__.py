"""The shared test vectors: every file in tests/vectors/, written by Python, checked by both sides.

``glasshead vectors`` regenerates them all (``generate``); ``glasshead vectors FILE ...`` only
the files named; ``--list`` lists them. The generators read the reference data
(``../shared/data``) and the built assets (running ``glasshead build`` first when they are stale).

Every JSON file follows one schema (``schema``): ``{description, generator, format_version,
constants, tolerance, [fixtures], cases: [{description, input, expected}]}``. One module per
topic makes the documents; ``GENERATORS`` says which files each writes.

This package is test tooling: it may import the pipeline and the settings. The kernels
(``geometry/``, ``epg/``) never import it.
"""

from dataclasses import dataclass


@dataclass(frozen=True)
class Generator:
    """``module:function`` returning {file name: document or bytes} for ``files``."""

    producer: str
    files: tuple


GENERATORS = (
    Generator("glasshead.vectors.constants:files", ("constants.json", "collision-constants.json")),
    Generator("glasshead.vectors.tongue:files",
              ("tongue-surface.json", "tongue-jaw.json", "tongue-bspline.json")),
    Generator("glasshead.vectors.face:files", ("face-rig.json",)),
    # after the tongue and face files: it reads their fixtures
    Generator("glasshead.vectors.flesh_points:files", ("flesh-points.json",)),
    Generator("glasshead.vectors.velum:files", ("velum.json",)),
    Generator("glasshead.vectors.tract_collision:files", ("tract-collision.json",)),
    Generator("glasshead.vectors.collision:files",
              ("collision-tables.bin", "collision-correct.json")),
    Generator("glasshead.vectors.epg_indices:files", ("epg-indices.json",)),
    Generator("glasshead.vectors.epg_contacts:files",
              ("epg-contacts-tables.bin", "epg-contacts.json")),
    Generator("glasshead.vectors.tube_acoustics:files", ("tube-acoustics.json",)),
    Generator("glasshead.vectors.area_function:files", ("area-function.json",)),
    Generator("glasshead.vectors.inversion:files", ("inversion.json",)),
)

#: Every file the package writes, in generation order.
VECTOR_FILES = tuple(name for generator in GENERATORS for name in generator.files)
