"""The `glasshead` command: build the assets, serve the app."""

import argparse
import sys
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


def serve(args):
    import uvicorn

    settings = get_settings()
    uvicorn.run("glasshead.api.app:app", host=args.host or settings.host,
                port=args.port or settings.port, log_level="info")
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
    serve_parser = commands.add_parser("serve", help="serve the API and the web app")
    serve_parser.add_argument("--host", help="default: HOST or 127.0.0.1")
    serve_parser.add_argument("--port", type=int, help="default: PORT or 8000")
    serve_parser.set_defaults(handler=serve)
    args = parser.parse_args(argv)
    return args.handler(args)


if __name__ == "__main__":
    sys.exit(main())
