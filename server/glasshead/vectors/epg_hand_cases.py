"""Small hand-made meshes about one electrode's probe, each with a known contact answer (part of
epg-contacts.json). Every triangle stands well clear of the probe's ends and sides (0.2 mm or
more), or straddles it by design (two triangles sharing an edge through the probe's axis)."""

import numpy as np

from glasshead.epg.contacts import contact_grid, electrode_contacts
from glasshead.epg.sequence import rows_to_strings
from glasshead.vectors.common import case, encode_f32


def hand_cases(layout, probes, contacts_hold):
    """Cases with ``input: {vertices (float32, base64), triangles, grid}`` about electrode R4C4;
    ``contacts_hold(vertices, triangles, probes_by_grid)`` must accept each (else RuntimeError)."""
    reading = probes["reading62"]
    grid = layout["grids"]["reading62"]
    electrode = next(e for e in grid["electrodes"] if e["id"] == "R4C4")
    e = np.array(electrode["position"])
    n = np.array(electrode["normal"])
    side = np.cross(n, [0.0, 0.0, 1.0])
    side /= np.linalg.norm(side)
    other = np.cross(n, side)

    def triangle(depth, offset=0.0, size=0.6):
        centre = e + depth * n + offset * side
        return [centre + size * (np.cos(a) * side + np.sin(a) * other)
                for a in (0.3, 0.3 + 2 * np.pi / 3, 0.3 + 4 * np.pi / 3)]

    cases = []

    def add(description, vertices, triangles):
        v = np.asarray(vertices, dtype=np.float32).astype(np.float64)
        t = np.asarray(triangles, dtype=np.int64)
        if not contacts_hold(v, t, {"reading62": reading}):
            raise RuntimeError(f"hand case {description!r} is near a contact boundary")
        contacts = electrode_contacts(v, t, reading)
        contacted = [i for i, c in zip(reading.ids, contacts, strict=True) if c]
        cases.append(case(description,
                          {"vertices": encode_f32(v.ravel()), "triangles": t.ravel().tolist(),
                           "grid": "reading62"},
                          {"rows": rows_to_strings(contact_grid(contacts, reading)),
                           "contacted": contacted}))

    one = [[0, 1, 2]]
    add("a triangle 0.5 mm in front of R4C4 contacts it and nothing else", triangle(0.5), one)
    add("a triangle 1.2 mm in front of R4C4 (beyond the tolerance) contacts nothing",
        triangle(1.2), one)
    add("a triangle 0.3 mm behind R4C4 (into the palate) contacts it", triangle(-0.3), one)
    add("a triangle 0.7 mm behind R4C4 (beyond the probe) contacts nothing", triangle(-0.7), one)
    add("a triangle 1 mm beside the probe of R4C4 contacts nothing", triangle(0.5, offset=1.0),
        one)
    # Two triangles whose shared edge passes exactly through the probe's axis.
    a, b = e + 0.5 * n + 0.8 * other, e + 0.5 * n - 0.8 * other
    add("a probe through the edge shared by two triangles contacts R4C4",
        [a, b, e + 0.5 * n + 0.8 * side, e + 0.5 * n - 0.8 * side], [[0, 1, 2], [1, 0, 3]])
    return cases
