# SPDX-License-Identifier: BSD-2-Clause
"""C programs over the C-Motion library (host/c), compiled here with cc as CMakeLists.txt builds
them: the library's generated sources (c-motion.h/.c, the ports' value references, the host
interfaces' table), then the library and the program in one cc call. `sanitize` adds one of the
runtimes (gcc's -fsanitize=thread, or address,undefined) to the library and the program alike."""

import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
HOST_C = ROOT / "host" / "c"
FMI_HEADERS = Path(__import__("fmpy").__file__).parent / "c-code"


def generate(out: Path) -> Path:
    """The library's generated sources, into out."""
    for generator in ("generate_cmotion.py", "generate_hosttime.py"):
        subprocess.run([sys.executable, str(ROOT / "modelDescription" / generator), str(out)], check=True)
    return out


def compile_program(
    source: Path, exe: Path, generated: Path, sanitize: str = "", warnings: bool = False, std: str = "c99"
) -> Path:
    """source linked with the library into exe; sanitize: "" or a -fsanitize= list; warnings: the
    project's own flags (-Wall -Wextra -Wpedantic -Werror) for library and program alike; std: the C
    standard of both."""
    library = [
        HOST_C / "PMDfmu.c",
        HOST_C / "PMDhosttime.c",
        HOST_C / "PMDdevice.c",
        HOST_C / "PMDserial.c",
        HOST_C / "PMDline.c",
        generated / "c-motion.c",
        generated / "PMDfmu_ports.c",
    ]
    flags = (
        ["-O1"]
        if not sanitize
        else ["-O1", "-g", "-fno-omit-frame-pointer", f"-fsanitize={sanitize}", "-fno-sanitize-recover=all"]
    )
    if warnings:
        flags += ["-Wall", "-Wextra", "-Wpedantic", "-Werror"]
    subprocess.run(
        [
            "cc",
            f"-std={std}",
            *flags,
            "-DPMD_HAVE_HOSTTIME",
            f"-I{HOST_C}",
            f"-I{generated}",
            f"-I{FMI_HEADERS}",
            *map(str, library),
            str(source),
            "-o",
            str(exe),
            "-pthread",
            "-ldl",
            "-lm",
        ],
        check=True,
    )
    return exe
