"""Bad input stops the build with a message that names what is wrong."""



from glasshead.cli import main
from glasshead.pipeline.sources import BADIN


def test_a_missing_data_directory_names_the_path_and_the_files(tmp_path, capsys):
    missing = tmp_path / "nowhere"
    assert main(["build", "--data-dir", str(missing), "--out", str(tmp_path / "out")]) == 2
    message = capsys.readouterr().err
    assert str(missing) in message
    assert "artisynth-badin/face.node" in message
    assert not (tmp_path / "out" / "manifest.json").exists()


def test_a_missing_file_is_named(data_copy, tmp_path, capsys):
    (data_copy / BADIN / "face.elem").unlink()
    assert main(["build", "--data-dir", str(data_copy), "--out", str(tmp_path / "out")]) == 2
    assert "face.elem" in capsys.readouterr().err


def test_a_corrupt_mesh_is_named(data_copy, tmp_path, capsys):
    (data_copy / BADIN / "tongue.obj").write_text("v 0.1 0.2 nan\nv 0 0 0\nv 1 1 1\nf 1 2 3\n")
    assert main(["build", "--data-dir", str(data_copy), "--out", str(tmp_path / "out")]) == 3
    assert "tongue.obj" in capsys.readouterr().err
    assert not (tmp_path / "out" / "manifest.json").exists()


def test_a_mesh_in_the_wrong_units_is_named(data_copy, tmp_path, capsys):
    path = data_copy / BADIN / "jaw.obj"
    lines = []
    for line in path.read_text().splitlines():  # metres -> millimetres: 1000 times too big
        if line.startswith("v "):
            x, y, z = (float(value) * 1000 for value in line.split()[1:4])
            line = f"v {x} {y} {z}"
        lines.append(line)
    path.write_text("\n".join(lines))
    assert main(["build", "--data-dir", str(data_copy), "--out", str(tmp_path / "out")]) == 3
    message = capsys.readouterr().err
    assert "jaw.obj" in message and "units" in message


def test_a_second_build_with_nothing_changed_is_a_no_op(built_assets, data_dir, capsys):
    before = (built_assets / "manifest.json").stat().st_mtime_ns
    assert main(["build", "--data-dir", str(data_dir), "--out", str(built_assets)]) == 0
    assert "up to date" in capsys.readouterr().out
    assert (built_assets / "manifest.json").stat().st_mtime_ns == before
