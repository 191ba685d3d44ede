"""The shared face rig vectors: well formed, reproduced by Python, and every vertex of every case
posed by node agrees with Python (the file stores only probes; this compares them all)."""

import itertools
import json
import re
import shutil
import subprocess

import numpy as np
import pytest

from glasshead.constants import FACE_VERTEX_TOLERANCE_MM
from glasshead.geometry import face_rig
from glasshead.settings import REPO_ROOT
from glasshead.vectors.face import RANDOM_CASES, fixed_sets, pose_case, random_draws
from vector_support import VECTORS_DIR, read_vectors, tol

pytestmark = pytest.mark.vectors
VECTORS = VECTORS_DIR / "face-rig.json"

# Poses every case with web/src/core/faceRig.js and writes float32 positions of every mesh, case
# after case, plus the gaps as JSON.
NODE_SCRIPT = """
import { readFileSync, writeFileSync } from 'node:fs';
import { FACE_RIG_MESHES as FACE_MESHES } from './web/src/core/constants.js';
import {
	createFaceRig, GAP_LIPS, lipValues, poseFace, restFaceRig,
} from './web/src/core/faceRig.js';
import { jawPose, POSE_LENGTH } from './web/src/core/jaw.js';
const [ vectorsPath, outPath ] = process.argv.slice( 1 );
const document = JSON.parse( readFileSync( vectorsPath, 'utf8' ) );
const { fixtures } = document;
const restOf = ( n ) => [ n, Float32Array.from( fixtures.rest[ n ] ) ];
const rest = Object.fromEntries( FACE_MESHES.map( restOf ) );
const rig = createFaceRig( fixtures.rig, rest );
const blank = ( n ) => [ n, new Float32Array( rest[ n ].length ) ];
const out = restFaceRig( rig, Object.fromEntries( FACE_MESHES.map( blank ) ) );
const size = FACE_MESHES.reduce( ( total, n ) => total + rest[ n ].length, 0 );
const all = new Float32Array( size * document.cases.length );
const values = new Float64Array( 5 );
const pose = new Float64Array( POSE_LENGTH );
const gaps = [];
document.cases.forEach( ( vector, k ) => {
	const { jaw_opening: opening, ...lips } = vector.input.params;
	poseFace( rig, lipValues( rig, lips, values ), jawPose( opening, fixtures.jaw, pose ), out );
	gaps.push( rig.gaps[ GAP_LIPS ] );
	let offset = size * k;
	for ( const n of FACE_MESHES ) { all.set( out[ n ], offset ); offset += out[ n ].length; }
} );
writeFileSync( outPath, Buffer.from( all.buffer ) );
console.log( JSON.stringify( { gaps } ) );
"""


@pytest.fixture(scope="module")
def document():
    return read_vectors("face-rig.json")


@pytest.fixture(scope="module")
def prepared(document):
    rest = {name: np.asarray(document["fixtures"]["rest"][name]).reshape(-1, 3)
            for name in face_rig.MESH_NAMES}
    return face_rig.prepare_meshes(document["fixtures"]["rig"], rest)


def test_the_file_holds_100_or_more_seeded_random_sets_with_the_jaw_and_unique_descriptions(
        document):
    random = [c for c in document["cases"] if c["description"].startswith("random set")]
    assert len(random) == RANDOM_CASES >= 100
    assert all(f"seed {document['constants']['seed']}" in c["description"] for c in random)
    openings = [c["input"]["params"]["jaw_opening"] for c in random]
    assert max(openings) - min(openings) > 8  # of the jaw's 0 to 10 degrees
    assert sum(c["input"]["params"]["lip_opening"] == 0.0 for c in random) >= 15
    descriptions = [c["description"] for c in document["cases"]]
    assert len(set(descriptions)) == len(descriptions)
    assert tol(document, "vertex_mm") == FACE_VERTEX_TOLERANCE_MM


def test_the_generator_draws_the_same_sets_again_from_the_seed(document):
    rig, seed = document["fixtures"]["rig"], document["constants"]["seed"]
    fixed = fixed_sets(rig)
    cases = document["cases"]
    assert [(d, p) for d, p in fixed] == [(c["description"], c["input"]["params"])
                                         for c in cases[:len(fixed)]]
    # Random sets name their draw (draws near a teeth decision were skipped).
    random = cases[len(fixed):]
    numbers = [int(re.search(r"draw (\d+)\)$", c["description"])[1]) for c in random]
    assert numbers == sorted(numbers) and len(set(numbers)) == len(numbers)
    draws = list(itertools.islice(random_draws(rig, seed), numbers[-1] + 1))
    for c, number in zip(random, numbers, strict=True):
        assert c["input"]["params"] == draws[number], c["description"]


def test_python_reproduces_every_expected_value(document, prepared):
    rig, jaw = document["fixtures"]["rig"], document["fixtures"]["jaw"]
    mm = tol(document, "stored_mm")
    for case in document["cases"]:
        posed, info = pose_case(rig, prepared, jaw, case["input"]["params"])
        expected, message = case["expected"], case["description"]
        for got, name in ((info["lip_gap"], "lip_gap_mm"), (info["natural_gap"], "natural_gap_mm"),
                          (info["closure"], "closure_mm")):
            np.testing.assert_allclose(got, expected[name], rtol=0, atol=mm,
                                       err_msg=f"{message}: {name}")
        # A count decided by floats: the generator keeps every case clear of its thresholds.
        assert info["teeth_clamped"] == expected["teeth_clamped"], message
        for name, probes in document["fixtures"]["probe_vertices"].items():
            np.testing.assert_allclose(posed[name][probes], expected["probe_positions"][name],
                                       rtol=0, atol=mm, err_msg=f"{message}: {name}")


def test_every_vertex_of_every_case_agrees_between_python_and_javascript(document, prepared,
                                                                          tmp_path):
    node = shutil.which("node")
    assert node, "node is needed to compare the JavaScript face rig"
    out = tmp_path / "faces.f32"
    result = subprocess.run([node, "--input-type=module", "-e", NODE_SCRIPT, str(VECTORS),
                             str(out)], cwd=REPO_ROOT, capture_output=True, text=True, check=True)
    gaps = json.loads(result.stdout)["gaps"]
    sizes = [len(prepared[name]["rest"]) for name in face_rig.MESH_NAMES]
    js = np.fromfile(out, dtype="<f4").reshape(len(document["cases"]), sum(sizes), 3)
    rig, jaw = document["fixtures"]["rig"], document["fixtures"]["jaw"]
    vertex_mm, gap_mm = tol(document, "vertex_mm"), tol(document, "gap_mm")
    worst = 0.0
    for k, case in enumerate(document["cases"]):
        posed, info = pose_case(rig, prepared, jaw, case["input"]["params"])
        python = np.concatenate([posed[name] for name in face_rig.MESH_NAMES])
        error = float(np.abs(js[k] - python).max())
        assert error <= vertex_mm, f"{case['description']}: {error} mm"
        assert abs(gaps[k] - info["lip_gap"]) <= gap_mm, case["description"]
        worst = max(worst, error)
    # float32 output: the worst difference is rounding, far inside the tolerance
    assert worst < 1e-4
    print(f"{len(document['cases'])} cases, {sum(sizes)} vertices each: within {worst:.2e} mm")
