"""The numpy SIMD targets to switch off for the narrowed run of the vector tests.

Prints, space-separated, every dispatch target of this numpy that this CPU has and that uses AVX2,
FMA3 or AVX512 (numpy 2.4 groups them as X86_V3 and X86_V4 and AVX512_*; older numpy names them
AVX2, FMA3, AVX512F, AVX512_SKX, ...): the value for NPY_DISABLE_CPU_FEATURES. numpy refuses to
disable a baseline feature or one it does not dispatch, so the list comes from what it reports.
Empty when the CPU has none of them (the narrowed run is then the default one).

With --check, exits 1 unless every target named in NPY_DISABLE_CPU_FEATURES is off in this
process, so that a run that did not narrow anything cannot pass for one that did.
"""

import os
import sys

try:
    from numpy._core._multiarray_umath import __cpu_dispatch__, __cpu_features__
except ImportError:  # numpy 1.x
    from numpy.core._multiarray_umath import __cpu_dispatch__, __cpu_features__

WIDE = ("AVX2", "FMA3", "X86_V3", "X86_V4")


def wide_targets():
    return [name for name in __cpu_dispatch__ if __cpu_features__.get(name)
            and (name in WIDE or name.startswith("AVX512"))]


def main(argv):
    if "--check" in argv:
        named = os.environ.get("NPY_DISABLE_CPU_FEATURES", "").split()
        still_on = [name for name in named if __cpu_features__.get(name)]
        if still_on:
            print(f"numpy still dispatches {' '.join(still_on)}", file=sys.stderr)
            return 1
        on = [name for name in __cpu_dispatch__ if __cpu_features__.get(name)]
        print(f"numpy SIMD narrowed: off {' '.join(named) or '(nothing to turn off)'}; "
              f"dispatch targets still on: {' '.join(on) or 'none (baseline only)'}")
        return 0
    print(" ".join(wide_targets()))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
