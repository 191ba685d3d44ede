"""The `glasshead` command, the one entry point of the package: build the assets, fit the tongue
to an observation, train the coarticulation constants, serve the app, bring the database up to
date, add a user, and write the files made from code (the shared test vectors, the lesson
format's JSON Schema)."""

import argparse
import json
import sys
import time
from pathlib import Path

from glasshead.geometry.meshio import MeshFormatError
from glasshead.settings import get_settings


def build(args):
    from glasshead.pipeline.build import run
    from glasshead.pipeline.sources import DataDirError
    from glasshead.pipeline.tract_collision_check import TractCollisionBuildError

    settings = get_settings()
    data_dir = Path(args.data_dir) if args.data_dir else settings.data_dir
    out = Path(args.out) if args.out else settings.assets_dir
    try:
        run(data_dir, out, force=args.force)
    except DataDirError as error:
        print(f"glasshead build: {error}", file=sys.stderr)
        return 2
    except MeshFormatError as error:
        print(f"glasshead build: corrupt or wrong mesh file: {error}", file=sys.stderr)
        return 3
    except TractCollisionBuildError as error:
        print(f"glasshead build: {error}", file=sys.stderr)
        return 4
    return 0


class ProgressBar:
    """A one-line text progress bar on a stream (stderr), redrawn at most every ``interval_s``:
    the share of the evaluation budget spent, the evaluations and the best objective."""

    def __init__(self, stream, width=30, interval_s=0.1):
        self.stream, self.width, self.interval_s = stream, width, interval_s
        self.last = 0.0
        self.drawn = False
        self.latest: tuple[int, float] | None = None

    def __call__(self, evaluations, best_error, fraction):
        self.latest = (evaluations, best_error)
        now = time.monotonic()
        if now - self.last < self.interval_s and fraction < 1.0:
            return
        self.last = now
        self.draw(evaluations, best_error, fraction)

    def draw(self, evaluations, best_error, fraction):
        filled = int(round(fraction * self.width))
        bar = "#" * filled + "." * (self.width - filled)
        self.stream.write(f"\rfitting [{bar}] {100 * fraction:5.1f} %  {evaluations:6d} "
                          f"evaluations  best {best_error:.4g}")
        self.stream.flush()
        self.drawn = True

    def close(self, finished=True):
        """End the line; a finished fit is drawn full (it may stop before its budget)."""
        if finished and self.latest is not None:
            self.draw(*self.latest, 1.0)
        if self.drawn:
            self.stream.write("\n")
            self.stream.flush()


def _read_fit_files(args):
    """(the observation, the files' names, the weights) of ``glasshead fit``'s files; raises
    FileNotFoundError naming a missing file, ``uploads.ObservationError`` for a bad one."""
    from glasshead import uploads

    def read(path: Path, kind: str) -> bytes:
        if not path.is_file():
            raise FileNotFoundError(f"no such file: {path}")
        with path.open("rb") as handle:  # never more than the kind's limit and one byte
            return handle.read(uploads.MAX_BYTES[kind] + 1)

    parts = {kind: getattr(args, kind) for kind in uploads.COMBINED_PARTS
             if getattr(args, kind, None)}
    if args.kind != "combined":
        if args.file is None or parts or args.weight:
            raise uploads.ObservationError(f"a {args.kind} fit takes one FILE, without "
                                           "--contour, --epg, --ema or --weight")
        path = Path(args.file)
        observation = uploads.read_observation(args.kind, read(path, args.kind), path.name,
                                               frame=args.frame)
        return observation, path.name, {}
    if args.file is not None:
        raise uploads.ObservationError("a combined fit takes --contour, --epg and --ema, two "
                                       "or more, not FILE")
    weights = {}
    for item in args.weight or ():
        part, _, value = item.partition("=")
        try:
            weights[part] = float(value)
        except ValueError:
            raise uploads.ObservationError(f"--weight {item!r}: expected PART=NUMBER, e.g. "
                                           "ema=2") from None
        if part not in parts or not 0 <= weights[part] <= uploads.MAX_PART_WEIGHT:
            raise uploads.ObservationError(f"--weight {item!r}: PART must be a file given "
                                           "(contour, epg or ema), the weight 0 to "
                                           f"{uploads.MAX_PART_WEIGHT:g}")
    contents: dict[str, tuple[bytes, str | None]] = {
        kind: (read(Path(name), kind), Path(name).name) for kind, name in parts.items()}
    observation = uploads.read_combined(contents, frame=args.frame, ema_frame=args.ema_frame)
    return observation, " + ".join(name or "" for _, name in contents.values()), weights


def fit(args):
    from glasshead import uploads
    from glasshead.asset_store import AssetStore, AssetUnavailableError
    from glasshead.fitting import authored
    from glasshead.jobs.fit_job import fit_inputs, save_fit

    settings = get_settings()
    path = args.file or "combined"
    try:
        observation, file_names, weights = _read_fit_files(args)
        inputs = fit_inputs(AssetStore(settings.assets_dir))
    except FileNotFoundError as error:
        print(f"glasshead fit: {error}", file=sys.stderr)
        return 2
    except uploads.ObservationError as error:
        print(f"glasshead fit: {path}: {error}", file=sys.stderr)
        return 3
    except AssetUnavailableError as error:
        print(f"glasshead fit: {error}", file=sys.stderr)
        return 2
    method = args.method or authored.default_method(args.kind, observation.points)
    bar = ProgressBar(sys.stderr)
    try:
        result = authored.fit_observation(inputs, args.kind, observation.points, method=method,
                                          max_evals=args.max_evals, progress=bar,
                                          name=args.name or "", weights=weights)
    except ValueError as error:
        bar.close(finished=False)
        print(f"glasshead fit: {path}: the fit failed: {error}", file=sys.stderr)
        return 4
    bar.close()
    name = args.name or file_names
    if weights:
        observation.source["options"] = {"weights": weights}
    document = {"name": name, "kind": args.kind, "method": method, "source": observation.source,
                **result}
    if args.save:
        document["id"] = save_fit(settings.database_url, observation, result, name=name,
                                  method=method, max_evals=args.max_evals)
        print(f"saved as fit {document['id']}", file=sys.stderr)
    text = json.dumps(document, indent=1)
    if args.out:
        Path(args.out).write_text(text + "\n")
    else:
        print(text)
    report = result["report"]
    print(f"{args.kind} fit: RMS {report['rms_mm']:.3f} mm, {report['evaluations']} evaluations, "
          f"{report['seconds']:.1f} s", file=sys.stderr)
    return 0


def train(args):
    """Train the coarticulation constants (docs/coarticulation.md) and write them; with
    ``--ema``, train the jaw against real articulography and report it (docs/ema.md)."""
    if args.ema:
        return train_ema(args)
    from glasshead.training import coarticulation

    max_evals = coarticulation.MAX_EVALS if args.max_evals is None else args.max_evals
    made = coarticulation.train(get_settings().assets_dir, max_evals=max_evals)
    coarticulation.print_report(made["report"])
    path = coarticulation.write_constants(made["constants"])
    print(f"wrote {path}")
    return 0


def train_ema(args):
    """The jaw trained against the HPRC recordings, each speaker held out: the report only."""
    from glasshead.asset_store import AssetStore
    from glasshead.flesh_point_assets import flesh_point_rig
    from glasshead.speech import ema_comparison
    from glasshead.training import ema_training

    settings = get_settings()
    store = AssetStore(settings.assets_dir)
    report = ema_training.run(ema_comparison.hprc_recordings(settings.data_dir),
                              store.get("phoneme_targets"), flesh_point_rig(store),
                              max_evals=args.max_evals or ema_training.MAX_EVALS)
    print(ema_training.format_report(report))
    return 0


def compare_ema(args):
    """Compare the head with real articulography (docs/ema.md): text tables, or JSON."""
    from glasshead.asset_store import AssetUnavailableError
    from glasshead.speech import ema_comparison

    settings = get_settings()
    try:
        paths = args.files or ema_comparison.hprc_recordings(settings.data_dir)
        report = ema_comparison.run(paths, settings.assets_dir)
    except (ValueError, OSError) as error:  # a bad file (EmaFormatError), a recording that
        # cannot be compared (ComparisonError) or phones the head cannot speak, each named
        print(f"glasshead compare-ema: {error}", file=sys.stderr)
        return 2
    except AssetUnavailableError as error:
        print(f"glasshead compare-ema: {error}", file=sys.stderr)
        return 3
    if args.json:
        print(json.dumps(report, indent=1))
    else:
        print(ema_comparison.format_report(report))
    return 0


def palate(args):
    """A learner's palate from a scan of their upper jaw (docs/palate.md): registered on the
    head, its collision tables and electrode layout rebuilt into a folder."""
    from glasshead.pipeline.learner_palate import ScanError, build_learner_palate

    path = Path(args.scan)
    try:
        data = path.read_bytes()
        report = build_learner_palate(
            data, path.suffix, get_settings().assets_dir, args.out,
            progress=lambda step, share: print(f"  {share:4.0%} {step}", file=sys.stderr))
    except (ScanError, OSError) as error:
        print(f"glasshead palate: {path}: {error}", file=sys.stderr)
        picture = getattr(error, "picture", None)
        if picture:
            shown = Path(f"{args.out}.residual.svg")
            shown.write_text(picture)
            print(f"glasshead palate: the scan as placed on the head's palate: {shown}",
                  file=sys.stderr)
        return 2
    residual = report["registration"]["mouth_facing_residual"]
    print(f"{args.out}: registered at {residual['rms_mm']} mm RMS on the palate and teeth "
          f"(95 % within {residual['p95_mm']} mm), {report['seconds']} s")
    return 0


def vectors(args):
    """Regenerate the shared test vectors (docs/vectors.md)."""
    from glasshead.vectors import VECTOR_FILES
    from glasshead.vectors.common import VECTORS_DIR
    from glasshead.vectors.generate import generate
    from glasshead.vectors.schema import VectorSchemaError

    if args.list:
        print("\n".join(VECTOR_FILES))
        return 0
    try:
        written = generate(args.names, args.out or VECTORS_DIR)
    except (ValueError, RuntimeError, VectorSchemaError) as exc:
        print(f"error: {exc}", file=sys.stderr)
        return 2
    print(f"wrote {len(written)} vector files")
    return 0


def lesson_schema(args):
    """Write the lesson format's JSON Schema (docs/lessons.md)."""
    from glasshead.lessons.schema import json_schema

    path = Path(args.out)
    path.write_text(json.dumps(json_schema(), indent=2, ensure_ascii=False) + "\n")
    print(f"wrote {path}")
    return 0


def serve(args):
    import uvicorn

    settings = get_settings()
    uvicorn.run("glasshead.api.app:app", host=args.host or settings.host,
                port=args.port or settings.port, log_level="info")
    return 0


def migrate(args):
    """Bring the database up to date (the application also does it at start-up)."""
    from sqlalchemy.engine import make_url

    from glasshead.store.db import upgrade_to_head

    url = get_settings().database_url
    upgrade_to_head()
    print(f"database at {make_url(url).render_as_string(hide_password=True)} is up to date")
    return 0


def user_create(args):
    """Add a user (the first admin, say): the password from a prompt or one line of stdin."""
    from sqlalchemy.orm import Session

    from glasshead.accounts import AccountError, check_password, create_user
    from glasshead.store.db import engine_for, upgrade_to_head

    if args.password_stdin:
        password = sys.stdin.readline().rstrip("\r\n")
    else:
        import getpass

        password = getpass.getpass(f"password for {args.username}: ")
        if password != getpass.getpass("the same password again: "):
            print("error: the two passwords differ; nothing was stored", file=sys.stderr)
            return 1
    engine = engine_for(get_settings().database_url)
    try:
        check_password(password)
        upgrade_to_head(engine)
        with Session(engine) as session:
            user = create_user(session, args.username, password, args.role, args.display_name)
            session.commit()
            print(f"created {user.role} {user.username} (user {user.id})", file=sys.stderr)
    except AccountError as error:
        print(f"error: {error}; nothing was stored", file=sys.stderr)
        return 1
    return 0


def main(argv=None):
    parser = argparse.ArgumentParser(prog="glasshead", description=__doc__)
    commands = parser.add_subparsers(dest="command", required=True)
    build_parser = commands.add_parser("build", help="build the assets that are stale")
    build_parser.add_argument("--data-dir", help="reference data (default: GLASSHEAD_DATA_DIR "
                                                 "or ../shared/data)")
    build_parser.add_argument("--out", help="output directory (default: assets/build)")
    build_parser.add_argument("--force", action="store_true", help="rebuild everything")
    build_parser.set_defaults(handler=build)
    fit_parser = commands.add_parser(
        "fit", help="fit the tongue to a contour, a surface or EPG frames (docs/fits.md)")
    fit_parser.add_argument("file", nargs="?", help="contour CSV, OBJ or PLY surface, EPG "
                            "recording or flesh points (not for --kind combined)")
    fit_parser.add_argument("--kind", required=True,
                            choices=("contour", "surface", "epg", "ema", "combined"))
    for part, what in (("contour", "a contour CSV"), ("epg", "an EPG recording"),
                       ("ema", "flesh points, CSV or JSON")):
        fit_parser.add_argument(f"--{part}", help=f"combined: {what}")
    fit_parser.add_argument("--weight", action="append", metavar="PART=W",
                            help="combined: a part's weight, 0 to 100 (default 1), e.g. ema=2")
    fit_parser.add_argument("--ema-frame", type=int,
                            help="combined: the frame of flesh-point tracks to fit")
    fit_parser.add_argument("--method", choices=("bobyqa", "praxis", "sbplx"),
                            help="the optimiser (default: bobyqa; sbplx for epg)")
    fit_parser.add_argument("--name", help="the target's name (default: the file's)")
    fit_parser.add_argument("--max-evals", type=int, help="cap on the fit's evaluations")
    fit_parser.add_argument("--frame", type=int,
                            help="epg: fit this frame (0-based) instead of the majority; ema: "
                                 "this frame of flesh-point tracks")
    fit_parser.add_argument("--out", help="write the result JSON here (default: stdout)")
    fit_parser.add_argument("--save", action="store_true",
                            help="store the result in the database as a fitted target")
    fit_parser.set_defaults(handler=fit)
    train_parser = commands.add_parser(
        "train", help="train the coarticulation constants against VocalTractLab's trajectories "
                      "and write speech/constants.json (docs/coarticulation.md)")
    train_parser.add_argument("--max-evals", type=int, default=None,
                              help="cap on the optimiser's evaluations (default: the trainer's)")
    train_parser.add_argument("--ema", action="store_true",
                              help="train the jaw's dominance and target gains against the HPRC "
                                   "recordings, each speaker held out, and report it (writes "
                                   "nothing; docs/ema.md)")
    train_parser.set_defaults(handler=train)
    compare_parser = commands.add_parser(
        "compare-ema", help="drive the head with real articulography's phone timings and "
                            "report how closely it follows the sensors (docs/ema.md)")
    compare_parser.add_argument("files", nargs="*", metavar="FILE",
                                help="EMA files, labels beside them (default: the HPRC "
                                     "recordings in the data directory)")
    compare_parser.add_argument("--json", action="store_true", help="print the report as JSON")
    compare_parser.set_defaults(handler=compare_ema)
    palate_parser = commands.add_parser(
        "palate", help="make a learner's palate from a scan of their upper jaw (STL, PLY or "
                       "OBJ): registered on the head, collision tables and electrodes rebuilt")
    palate_parser.add_argument("scan", metavar="SCAN", help="the scan file")
    palate_parser.add_argument("--out", required=True, metavar="DIR",
                               help="the folder to write (replaced only when all is written)")
    palate_parser.set_defaults(handler=palate)
    vectors_parser = commands.add_parser(
        "vectors", help="regenerate the shared test vectors in tests/vectors (docs/vectors.md)")
    vectors_parser.add_argument("names", nargs="*", metavar="FILE",
                                help="vector files to write (default: all)")
    vectors_parser.add_argument("--out", help="output directory (default: tests/vectors)")
    vectors_parser.add_argument("--list", action="store_true", help="list the files and stop")
    vectors_parser.set_defaults(handler=vectors)
    schema_parser = commands.add_parser(
        "lesson-schema", help="write the lesson format's JSON Schema (docs/lessons.md)")
    schema_parser.add_argument("out", nargs="?", default="docs/lesson.schema.json",
                               help="where (default: docs/lesson.schema.json)")
    schema_parser.set_defaults(handler=lesson_schema)
    serve_parser = commands.add_parser("serve", help="serve the API and the web app")
    serve_parser.add_argument("--host", help="default: HOST or 127.0.0.1")
    serve_parser.add_argument("--port", type=int, help="default: PORT or 8000")
    serve_parser.set_defaults(handler=serve)
    migrate_parser = commands.add_parser(
        "migrate", help="apply the database migrations (the app does it at start-up)")
    migrate_parser.set_defaults(handler=migrate)
    user_parser = commands.add_parser("user", help="manage the people who sign in "
                                                   "(docs/auth.md)")
    user_commands = user_parser.add_subparsers(dest="user_command", required=True)
    create_parser = user_commands.add_parser("create", help="add a user, e.g. the first admin")
    create_parser.add_argument("username", help="unique; an email address will do")
    create_parser.add_argument("--role", required=True,
                               choices=("author", "teacher", "clinician", "admin"))
    create_parser.add_argument("--display-name", help="the name shown (default: the username)")
    create_parser.add_argument("--password-stdin", action="store_true",
                               help="read the password from the first line of stdin instead of "
                                    "a prompt")
    create_parser.set_defaults(handler=user_create)
    args = parser.parse_args(argv)
    return args.handler(args)


if __name__ == "__main__":
    sys.exit(main())
