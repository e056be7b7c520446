"""``python -m geocold``: the ``geocold-cl`` command line, run in this process.

``python -m geocold scene.obj -o out.png`` takes every option ``geocold-cl`` takes
(``--help`` lists them) and exits with the same codes; the kernels and the image module
are the package's own unless GEOCOLD_KERNEL_DIR / GEOCOLD_IMAGE_MODULE say otherwise.
(The Vulkan commands, ``--preview`` and ``--cross-check``, are not in the package's build.)
"""

import os
import sys

from . import _HERE, _IMAGE_MODULE, _geocold


def main(argv=None) -> int:
    """Runs the command line on ``argv`` (default: ``sys.argv[1:]``) and returns its exit code."""
    os.environ.setdefault("GEOCOLD_KERNEL_DIR", str(_HERE / "kernels"))
    if _IMAGE_MODULE.exists():
        os.environ.setdefault("GEOCOLD_IMAGE_MODULE", str(_IMAGE_MODULE))
    sys.stdout.flush()
    return _geocold.cli_main(list(sys.argv[1:] if argv is None else argv))


if __name__ == "__main__":
    sys.exit(main())
