"""The shared tongue vectors: well formed, reproduced by Python, and every vertex of every set
evaluated by node agrees with Python (the file stores only probes; this compares them all)."""

import json
import shutil
import subprocess

import numpy as np
import pytest

from glasshead.constants import TONGUE_VERTEX_TOLERANCE_MM, TONGUE_VOLUME_RELATIVE_TOLERANCE
from glasshead.geometry.bspline import basis_table
from glasshead.geometry.tongue_surface import TongueRig
from glasshead.settings import REPO_ROOT
from glasshead.vectors.tongue import RANDOM_CASES, parameter_sets
from vector_support import VECTORS_DIR, read_vectors, tol

pytestmark = pytest.mark.vectors

# Reads the vector file, evaluates every set with web/src/core/tongue.js, and writes float32
# positions and normals of all sets, one after the other, plus the volumes as JSON.
NODE_SCRIPT = """
import { readFileSync, writeFileSync } from 'node:fs';
import { meshVolume } from './web/src/core/meshVolume.js';
import { TongueRig } from './web/src/core/tongue.js';
const [ vectorsPath, outPath ] = process.argv.slice( 1 );
const document = JSON.parse( readFileSync( vectorsPath, 'utf8' ) );
const rig = new TongueRig( document.fixtures.rig );
const surface = rig.createSurface();
const values = new Float64Array( rig.parameterCount );
const size = 3 * rig.vertexCount;
const out = new Float32Array( 2 * size * document.cases.length );
const volumes = [];
document.cases.forEach( ( vector, k ) => {
	rig.evaluate( rig.valuesFrom( vector.input.params, values ), surface );
	out.set( surface.positions, 2 * size * k );
	out.set( surface.normals, 2 * size * k + size );
	volumes.push( meshVolume( surface.positions, surface.index ) );
} );
writeFileSync( outPath, Buffer.from( out.buffer ) );
console.log( JSON.stringify( { vertexCount: rig.vertexCount, volumes } ) );
"""


@pytest.fixture(scope="module")
def document():
    return read_vectors("tongue-surface.json")


@pytest.fixture(scope="module")
def rig(document):
    return TongueRig(document["fixtures"]["rig"])


def test_the_file_holds_200_or_more_seeded_random_sets_and_unique_descriptions(document):
    random = [c for c in document["cases"] if c["description"].startswith("random set")]
    assert len(random) == RANDOM_CASES >= 200
    assert all(f"seed {document['constants']['seed']}" in c["description"] for c in random)
    descriptions = [c["description"] for c in document["cases"]]
    assert len(set(descriptions)) == len(descriptions)
    assert tol(document, "vertex_mm") == TONGUE_VERTEX_TOLERANCE_MM
    assert tol(document, "volume_relative") == TONGUE_VOLUME_RELATIVE_TOLERANCE


def test_the_random_sets_cover_every_range_including_the_jaw(document, rig):
    random = np.array([[c["input"]["params"][n] for n in rig.parameter_names]
                       for c in document["cases"] if c["description"].startswith("random set")])
    span = (random.max(axis=0) - random.min(axis=0)) / (rig.maximum - rig.minimum)
    assert np.all(span > 0.9), dict(zip(rig.parameter_names, span, strict=True))
    assert np.all(random >= rig.minimum) and np.all(random <= rig.maximum)


def test_the_generator_draws_the_same_sets_again_from_the_seed(document, rig):
    again = parameter_sets(rig, seed=document["constants"]["seed"])
    assert [d for d, _ in again] == [c["description"] for c in document["cases"]]
    assert [p for _, p in again] == [c["input"]["params"] for c in document["cases"]]


def test_python_reproduces_every_expected_value(document, rig):
    probes = document["fixtures"]["probe_vertices"]
    mm, mm3 = tol(document, "stored_mm"), tol(document, "stored_volume_mm3")
    for case in document["cases"]:
        surface = rig.evaluate(rig.values_from(case["input"]["params"]))
        expected = case["expected"]
        message = case["description"]
        assert (len(surface.vertices), len(surface.triangles)) == \
            (expected["vertex_count"], expected["triangle_count"]), message
        v = surface.vertices
        for got, name in ((v[probes], "probe_positions"), (v.mean(axis=0), "centroid"),
                          (v.min(axis=0), "bounds_min"), (v.max(axis=0), "bounds_max")):
            np.testing.assert_allclose(got, expected[name], rtol=0, atol=mm,
                                       err_msg=f"{message}: {name}")
        np.testing.assert_allclose(surface.volume, expected["volume_mm3"], rtol=0, atol=mm3,
                                   err_msg=message)


def test_every_vertex_of_every_set_agrees_between_python_and_javascript(document, rig, tmp_path):
    node = shutil.which("node")
    assert node, "node is needed to compare the JavaScript evaluator"
    out = tmp_path / "surfaces.f32"
    result = subprocess.run([node, "--input-type=module", "-e", NODE_SCRIPT,
                             str(VECTORS_DIR / "tongue-surface.json"), str(out)],
                            cwd=REPO_ROOT, capture_output=True, text=True, check=True)
    report = json.loads(result.stdout)
    cases = document["cases"]
    js = np.fromfile(out, dtype="<f4").reshape(len(cases), 2, report["vertexCount"], 3)
    vertex_mm, normal = tol(document, "vertex_mm"), tol(document, "normal")
    volume_relative = tol(document, "volume_relative")
    worst_vertex = worst_normal = worst_volume = 0.0
    for k, case in enumerate(cases):
        surface = rig.evaluate(rig.values_from(case["input"]["params"]))
        vertex_error = np.abs(js[k, 0] - surface.vertices).max()
        assert vertex_error <= vertex_mm, f"{case['description']}: {vertex_error}"
        normal_error = np.abs(js[k, 1] - surface.normals).max()
        assert normal_error <= normal, f"{case['description']}: normals off by {normal_error}"
        volume_error = abs(report["volumes"][k] / surface.volume - 1)
        assert volume_error <= volume_relative, case["description"]
        worst_vertex = max(worst_vertex, vertex_error)
        worst_normal = max(worst_normal, normal_error)
        worst_volume = max(worst_volume, volume_error)
    # float32 output: the worst difference is rounding, far inside the tolerance
    assert worst_vertex < 1e-4 and worst_volume < 1e-6
    print(f"{len(cases)} sets: vertices within {worst_vertex:.2e} mm, normals {worst_normal:.2e}, "
          f"volumes {worst_volume:.2e} relative")


def test_the_bspline_vectors_reproduce_in_python():
    document = read_vectors("tongue-bspline.json")
    for case in document["cases"]:
        first, values = basis_table(case["input"]["knots"], case["input"]["degree"],
                                    case["input"]["params"])
        np.testing.assert_array_equal(first, case["expected"]["first"])  # spans: integers
        np.testing.assert_allclose(values, case["expected"]["values"], rtol=0,
                                   atol=tol(document, "basis"), err_msg=case["description"])
