"""`glasshead fit`: the same fit as the API, in this process, with a progress bar on stderr."""

import json

import numpy as np
import pytest
from sqlalchemy.orm import Session

from glasshead.cli import main
from glasshead.fitting import fit2d
from glasshead.settings import get_settings
from glasshead.store.db import engine_for
from glasshead.store.fit_jobs import FitJob


@pytest.fixture(scope="module")
def contour_file(built_assets, tmp_path_factory):
    shapes = json.loads((built_assets / "vtl-observations.json").read_text())["shapes"]
    outline = np.array(next(s for s in shapes if s["name"] == "i")["tongue_outline"])
    path = tmp_path_factory.mktemp("cli") / "i.csv"
    path.write_text("x_mm,y_mm\n" + "".join(f"{x!r},{y!r}\n" for x, y in outline.tolist()))
    return path, outline


def test_a_contour_fit_draws_its_progress_and_prints_the_target_as_json(
        contour_file, built_assets, capsys):
    path, outline = contour_file
    assert main(["fit", str(path), "--kind", "contour", "--max-evals", "300"]) == 0
    out, err = capsys.readouterr()
    assert "fitting [" in err and "100.0 %" in err and "contour fit: RMS" in err
    result = json.loads(out)
    rig, _ = fit2d.load_inputs(built_assets)
    expected = fit2d.fit_outline(rig, outline, max_evals=300)
    assert result["report"]["rms_mm"] == pytest.approx(expected.rms_mm, abs=1e-9)
    assert result["method"] == "bobyqa" and result["name"] == "i.csv"
    assert set(rig.parameter_names) <= set(result["params"])


def test_save_stores_the_fit_as_a_finished_target(contour_file, tmp_path, monkeypatch, capsys):
    path, _ = contour_file
    url = f"sqlite:///{tmp_path / 'cli.sqlite3'}"
    monkeypatch.setenv("GLASSHEAD_DATABASE_URL", url)
    get_settings.cache_clear()
    try:
        out_file = tmp_path / "fit.json"
        assert main(["fit", str(path), "--kind", "contour", "--max-evals", "100", "--save",
                     "--name", "my /i/", "--out", str(out_file)]) == 0
    finally:
        get_settings.cache_clear()
    saved = json.loads(out_file.read_text())
    assert capsys.readouterr().out == ""  # the result went to --out
    engine = engine_for(url)
    with Session(engine) as session:
        job = session.get(FitJob, saved["id"])
        assert (job.state, job.name, job.kind) == ("done", "my /i/", "contour")
        assert job.params == saved["params"] and job.report["evaluations"] == 100
    engine.dispose()


def test_a_missing_file_exits_2_and_a_bad_one_3_each_with_a_message(tmp_path, capsys):
    assert main(["fit", str(tmp_path / "none.csv"), "--kind", "contour"]) == 2
    assert "no such file" in capsys.readouterr().err
    bad = tmp_path / "bad.csv"
    bad.write_text("x_mm,y_mm\n0,0\n5,oops\n")
    assert main(["fit", str(bad), "--kind", "contour"]) == 3
    err = capsys.readouterr().err
    assert "bad.csv" in err and "line 3" in err


def test_an_unknown_kind_is_refused_by_the_command_line(tmp_path, capsys):
    with pytest.raises(SystemExit) as stopped:
        main(["fit", str(tmp_path / "x.csv"), "--kind", "ultrasound"])
    assert stopped.value.code == 2 and "--kind" in capsys.readouterr().err


def test_a_combined_fit_takes_its_parts_and_weights_and_reports_each_term(
        contour_file, tmp_path, capsys):
    path, _ = contour_file
    sensors = tmp_path / "jaw.csv"
    sensors.write_text("point,x_mm,y_mm\nlower_incisor,24.5,-9.5\n")
    assert main(["fit", "--kind", "combined", "--contour", str(path), "--ema", str(sensors),
                 "--weight", "ema=3", "--max-evals", "300"]) == 0
    out, err = capsys.readouterr()
    result = json.loads(out)
    assert result["name"] == "i.csv + jaw.csv" and result["method"] == "bobyqa"
    assert result["source"]["options"] == {"weights": {"ema": 3.0}}
    terms = result["report"]["terms"]
    assert terms["contour"]["weight"] == 1.0 and terms["ema"]["weight"] == 30.0
    assert terms["ema"]["errors_mm"]["lower_incisor"] < 1.0
    assert "combined fit: RMS" in err


def test_combined_parts_or_weights_that_do_not_fit_exit_3_naming_them(contour_file, tmp_path,
                                                                      capsys):
    path, _ = contour_file
    assert main(["fit", "--kind", "combined", "--contour", str(path)]) == 3
    assert "at least two" in capsys.readouterr().err
    sensors = tmp_path / "s.csv"
    sensors.write_text("TT,20,10\n")
    assert main(["fit", "--kind", "combined", "--contour", str(path), "--ema", str(sensors),
                 "--weight", "epg=2"]) == 3
    assert "--weight 'epg=2'" in capsys.readouterr().err
    assert main(["fit", str(path), "--kind", "contour", "--ema", str(sensors)]) == 3
    assert "takes one FILE" in capsys.readouterr().err
    assert main(["fit", "--kind", "combined", "--contour", str(tmp_path / "none.csv"),
                 "--ema", str(sensors)]) == 2
    assert "no such file" in capsys.readouterr().err
