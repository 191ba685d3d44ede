"""The shared face rig vectors: well formed, reproduced by Python, and every vertex of every case
posed by node agrees with Python (the file stores only probes; this compares them all)."""

import json
import shutil
import subprocess
from pathlib import Path

import numpy as np
import pytest

from glasshead.constants import FACE_VERTEX_TOLERANCE_MM
from glasshead.geometry import face_rig
from glasshead.geometry.face_vectors import RANDOM_CASES, parameter_sets, pose_case
from glasshead.settings import REPO_ROOT

VECTORS = Path(__file__).parent / "vectors" / "face-rig.json"

# Poses every case with web/src/core/faceRig.js and writes float32 positions of every mesh, case
# after case, plus the gaps as JSON.
NODE_SCRIPT = """
import { readFileSync, writeFileSync } from 'node:fs';
import { applyFaceRig, createFaceRig, FACE_MESHES, GAP_LIPS, lipValues, restFaceRig } from './web/src/core/faceRig.js';
import { jawPose, POSE_LENGTH } from './web/src/core/jaw.js';
const [ vectorsPath, outPath ] = process.argv.slice( 1 );
const document = JSON.parse( readFileSync( vectorsPath, 'utf8' ) );
const rest = Object.fromEntries( FACE_MESHES.map( ( n ) => [ n, Float32Array.from( document.rest[ n ] ) ] ) );
const rig = createFaceRig( document.rig, rest );
const out = restFaceRig( rig, Object.fromEntries( FACE_MESHES.map( ( n ) => [ n, new Float32Array( rest[ n ].length ) ] ) ) );
const size = FACE_MESHES.reduce( ( total, n ) => total + rest[ n ].length, 0 );
const all = new Float32Array( size * document.cases.length );
const values = new Float64Array( 5 );
const pose = new Float64Array( POSE_LENGTH );
const gaps = [];
document.cases.forEach( ( vector, k ) => {
	const { jaw_opening: opening, ...lips } = vector.input.params;
	applyFaceRig( rig, lipValues( rig, lips, values ), jawPose( opening, document.jaw, pose ), out );
	gaps.push( rig.gaps[ GAP_LIPS ] );
	let offset = size * k;
	for ( const n of FACE_MESHES ) { all.set( out[ n ], offset ); offset += out[ n ].length; }
} );
writeFileSync( outPath, Buffer.from( all.buffer ) );
console.log( JSON.stringify( { gaps } ) );
"""


@pytest.fixture(scope="module")
def document():
    return json.loads(VECTORS.read_text())


@pytest.fixture(scope="module")
def prepared(document):
    rest = {name: np.asarray(document["rest"][name]).reshape(-1, 3)
            for name in face_rig.MESH_NAMES}
    return face_rig.prepare_meshes(document["rig"], rest)


def test_the_file_holds_100_or_more_seeded_random_sets_with_the_jaw_and_unique_descriptions(
        document):
    random = [c for c in document["cases"] if c["description"].startswith("random set")]
    assert len(random) == RANDOM_CASES >= 100
    assert all(f"seed {document['seed']}" in c["description"] for c in random)
    openings = [c["input"]["params"]["jaw_opening"] for c in random]
    assert max(openings) - min(openings) > 20
    assert sum(c["input"]["params"]["lip_opening"] == 0.0 for c in random) >= 15
    descriptions = [c["description"] for c in document["cases"]]
    assert len(set(descriptions)) == len(descriptions)
    assert document["tolerance"] == {"vertex_mm": FACE_VERTEX_TOLERANCE_MM}


def test_the_generator_draws_the_same_sets_again_from_the_seed(document):
    again = parameter_sets(document["rig"], seed=document["seed"])
    assert [d for d, _ in again] == [c["description"] for c in document["cases"]]
    assert [p for _, p in again] == [c["input"]["params"] for c in document["cases"]]


def test_python_reproduces_every_expected_value(document, prepared):
    for case in document["cases"]:
        posed, info = pose_case(document["rig"], prepared, document["jaw"], case["input"]["params"])
        expected, message = case["expected"], case["description"]
        np.testing.assert_allclose(info["lip_gap"], expected["lip_gap_mm"], atol=1e-5,
                                   err_msg=message)
        np.testing.assert_allclose(info["natural_gap"], expected["natural_gap_mm"], atol=1e-5)
        np.testing.assert_allclose(info["closure"], expected["closure_mm"], atol=1e-5)
        assert info["teeth_clamped"] == expected["teeth_clamped"], message
        for name, probes in document["probe_vertices"].items():
            np.testing.assert_allclose(posed[name][probes], expected["probe_positions"][name],
                                       atol=1e-5, err_msg=f"{message}: {name}")


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
    worst = 0.0
    for k, case in enumerate(document["cases"]):
        posed, info = pose_case(document["rig"], prepared, document["jaw"], case["input"]["params"])
        python = np.concatenate([posed[name] for name in face_rig.MESH_NAMES])
        error = float(np.abs(js[k] - python).max())
        assert error <= FACE_VERTEX_TOLERANCE_MM, f"{case['description']}: {error} mm"
        assert abs(gaps[k] - info["lip_gap"]) <= 1e-4, case["description"]
        worst = max(worst, error)
    # float32 output: the worst difference is rounding, far inside the tolerance
    assert worst < 1e-4
    print(f"{len(document['cases'])} cases, {sum(sizes)} vertices each: within {worst:.2e} mm")
