"""The browser's constants are generated from constants.py: the committed module is up to date."""

import json
import shutil
import subprocess

from glasshead import shared_constants
from glasshead.settings import REPO_ROOT

GENERATED = REPO_ROOT / shared_constants.OUTPUT


def test_the_committed_browser_constants_are_what_constants_py_generates():
    assert GENERATED.read_text(encoding="utf-8") == shared_constants.module_text(), (
        f"{shared_constants.OUTPUT} is stale: regenerate it from the repository root with "
        f"`{shared_constants.COMMAND}` and commit it")


def test_every_constant_is_shared_with_its_comment_and_the_module_says_how_it_is_made():
    text = shared_constants.module_text()
    assert "Generated from server/glasshead/constants.py" in text.splitlines()[0]
    assert shared_constants.COMMAND in text
    for name in shared_constants.shared_names():
        assert f"export const {name} = " in text, name
    assert "/** Electrodes on the palate: 8 * 8 minus the two missing corners of R1. */\n" \
           "export const EPG_ELECTRODES = 62;" in text


def test_the_generated_module_reads_back_as_the_python_values_frozen(tmp_path):
    node = shutil.which("node")
    assert node, "node is needed to read the generated module"
    module = tmp_path / "shared.generated.mjs"
    module.write_text(shared_constants.module_text(), encoding="utf-8")
    script = (f"import * as c from {json.dumps(module.as_uri())};\n"
              "const frozen = ( v ) => v === null || typeof v !== 'object' || "
              "( Object.isFrozen( v ) && Object.values( v ).every( frozen ) );\n"
              "const all = Object.values( c ).every( frozen );\n"
              "console.log( JSON.stringify( { values: c, frozen: all } ) );")
    result = subprocess.run([node, "--input-type=module", "-e", script], capture_output=True,
                            text=True, check=True)
    read = json.loads(result.stdout)
    assert read["frozen"]
    expected = {name: shared_constants.plain(getattr(shared_constants.constants, name))
                for name in shared_constants.shared_names()}
    assert read["values"] == json.loads(json.dumps(expected))


def test_values_become_javascript_literals():
    literal = shared_constants.literal
    assert literal(1e-09) == "1e-9"
    assert literal(-1.5) == "- 1.5"
    assert literal("it's") == "'it\\'s'"
    assert literal((1, 2)) == "Object.freeze( [ 1, 2 ] )"
    assert literal({"a-b": [], "c": {}}) == (
        "Object.freeze( { 'a-b': Object.freeze( [] ), c: Object.freeze( {} ) } )")
    assert literal(["x" * 60, "y" * 60]).count("\n") == 3
