# SPDX-License-Identifier: BSD-2-Clause
"""The binaries for other desktops (CMakeLists.txt's PMD_PLATFORMS, `pmdfmu build --platforms all`):
Windows x86_64 in both FMUs (FMI 2 win64, FMI 3 x86_64-windows; mingw-w64) and Linux aarch64 in the
FMI 3 FMUs. A small C master (tests/c/fmi_master.c), built for each platform, loads each binary of
the FMUs it carries under Wine or qemu-user, runs the seed's external-profile example
(examples/two_axis.script through the `script` parameter) and a closed loop of chip and plant
(examples/systems/move.script), and prints rows that must equal, bit for bit, the rows of the same
master built for this machine on the linux64 binaries.

The module builds the FMUs with every platform whose cross compiler is installed (.ci/run installs
them, and Wine and qemu-user) into build-platforms/, incrementally; a platform without its compiler
or its emulator is skipped, naming the Debian package that brings it."""

import re
import shutil
import subprocess
import sys
import zipfile
from pathlib import Path

import fmpy
import numpy as np
import pytest

import pmdfmu

REPO = Path(__file__).resolve().parent.parent
EXAMPLES = REPO / "examples"
FMI_HEADERS = Path(fmpy.__file__).parent / "c-code"
MASTER = REPO / "tests" / "c" / "fmi_master.c"
BUILD = REPO / "build-platforms"
STEPS_PROFILE = 3100  # two_axis.script's last call is at cycle 3000
STEPS_LOOP = 600  # move.script's move is under way (accelerating to 10 counts/cycle)

# platform: (cross compiler, its Debian package, emulator command or None, FMI 2 folder, FMI 3 folder,
# the library's suffix)
PLATFORMS = {
    "x86_64-windows": ("x86_64-w64-mingw32-gcc", "gcc-mingw-w64-x86-64", "wine", "win64", "x86_64-windows", ".dll"),
    "aarch64-linux": ("aarch64-linux-gnu-gcc", "gcc-aarch64-linux-gnu", "qemu", None, "aarch64-linux", ".so"),
}
NATIVE = ("gcc", "gcc", None, "linux64", "x86_64-linux", ".so")


def wine() -> str | None:
    """Debian's wine64 puts its loader outside PATH (the `wine` package adds /usr/bin/wine)."""
    return (
        shutil.which("wine64")
        or shutil.which("wine")
        or ("/usr/lib/wine/wine64" if Path("/usr/lib/wine/wine64").exists() else None)
    )


def missing(platform: str) -> str | None:
    """Why a platform cannot be built and run here, or None."""
    compiler, package, emulator, *_ = PLATFORMS[platform]
    if not shutil.which(compiler):
        return f"{compiler} is not installed (apt-get install {package})"
    if emulator == "wine" and not wine():
        return "Wine is not installed (apt-get install wine64)"
    if emulator == "qemu" and not shutil.which("qemu-aarch64"):
        return "qemu-aarch64 is not installed (apt-get install qemu-user)"
    return None


AVAILABLE = [p for p in PLATFORMS if not missing(p)]

pytestmark = pytest.mark.slow  # a build of every FMU (tests/README.md: ./dev test -m "not slow" leaves it out)


@pytest.fixture(scope="module")
def fmus(tmp_path_factory):
    """The four FMUs built by `pmdfmu build --platforms` with every platform available here, unpacked:
    {(model, fmi_version): folder}."""
    if not AVAILABLE:
        pytest.skip("; ".join(missing(p) for p in PLATFORMS))
    command = [sys.executable, "-c", "from pmdfmu.cli import console; console()"]
    command += ["build", "--source", str(REPO), "--build-dir", str(BUILD), "--platforms", ",".join(AVAILABLE)]
    result = subprocess.run(command, capture_output=True, text=True)
    assert result.returncode == 0, result.stdout[-3000:] + result.stderr[-3000:]
    out = tmp_path_factory.mktemp("fmus")
    unpacked = {}
    for model, identifier in (("chip", "PMDMotionProcessor"), ("plant", "pmdplant")):
        for version in (2, 3):
            folder = out / f"{identifier}-fmi{version}"
            with zipfile.ZipFile(BUILD / f"{identifier}-fmi{version}.fmu") as z:
                z.extractall(folder)
            unpacked[model, version] = folder
    return unpacked


@pytest.fixture(scope="module")
def masters(tmp_path_factory):
    """fmi_master built for this machine and for each available platform: {platform: executable}."""
    out = tmp_path_factory.mktemp("masters")
    built = {}
    for platform, (compiler, *_rest, suffix) in [("native", NATIVE)] + [(p, PLATFORMS[p]) for p in AVAILABLE]:
        exe = out / (f"fmi_master-{platform}" + (".exe" if suffix == ".dll" else ""))
        flags = ["-static", "-D__USE_MINGW_ANSI_STDIO=1"] if suffix == ".dll" else ["-ldl"]
        command = [compiler, "-std=c99", "-O1", "-Wall", "-Wextra", "-Wpedantic", "-Werror", f"-I{FMI_HEADERS}"]
        subprocess.run(command + [str(MASTER), "-o", str(exe)] + flags, check=True)
        built[platform] = exe
    return built


@pytest.fixture(scope="module")
def wine_prefix(tmp_path_factory):
    """A Wine prefix of the test's own (its first start takes some seconds)."""
    prefix = tmp_path_factory.mktemp("wine")
    return prefix


def windows_path(path: Path) -> str:
    """Wine's drive Z: is the root folder."""
    return "Z:" + str(path).replace("/", "\\")


class Run:
    """One run of the master: its FMUs, start values, wires and columns, for one platform."""

    def __init__(self, fmus, platform: str, version: int):
        self.fmus, self.platform, self.version = fmus, platform, version
        self.args: list[str] = []
        self.descriptions: list = []

    def path(self, path: Path) -> str:
        return windows_path(path) if self.platform == "x86_64-windows" else str(path)

    def fmu(self, model: str) -> int:
        folder = self.fmus[model, self.version]
        md = fmpy.read_model_description(str(folder))
        _, _, _, folder2, folder3, suffix = NATIVE if self.platform == "native" else PLATFORMS[self.platform]
        binaries = folder / "binaries" / (folder2 if self.version == 2 else folder3)
        library = binaries / (md.coSimulation.modelIdentifier + suffix)
        resources = folder / "resources"
        if self.version == 2:
            where = ("file:///" + self.path(resources).replace("\\", "/")).replace("file:////", "file:///")
        else:
            where = self.path(resources) + ("\\" if self.platform == "x86_64-windows" else "/")
        self.args += ["fmu", str(self.version), self.path(library), where, md.guid]
        self.descriptions.append({v.name: v for v in md.modelVariables})
        return len(self.descriptions) - 1

    def variable(self, k: int, name: str) -> list[str]:
        v = self.descriptions[k][name]
        return [str(k), v.type, str(v.valueReference)]

    def set(self, k: int, name: str, value: str):
        self.args += ["set", *self.variable(k, name), value]

    def wire(self, k: int, name: str, k2: int, name2: str):
        self.args += ["wire", *self.variable(k, name), str(k2), str(self.descriptions[k2][name2].valueReference)]

    def out(self, k: int, *names: str):
        for name in names:
            self.args += ["out", *self.variable(k, name)]

    def rows(self, masters, steps: int, wine_prefix) -> list[str]:
        command = [str(masters[self.platform]), str(steps), "1e-4", *self.args]
        env = None
        if self.platform == "x86_64-windows":
            command = [wine(), *command]
            env = {
                "WINEPREFIX": str(wine_prefix),
                "WINEDEBUG": "-all",
                "WINEDLLOVERRIDES": "mscoree,mshtml=",
                "PATH": "/usr/bin:/bin",
                "HOME": str(wine_prefix),
            }
        elif self.platform == "aarch64-linux":
            command = ["qemu-aarch64", "-L", "/usr/aarch64-linux-gnu", *command]
        result = subprocess.run(command, capture_output=True, text=True, env=env, cwd=EXAMPLES, timeout=600)
        assert result.returncode == 0, f"{self.platform} FMI {self.version}: {result.stderr[-3000:]}"
        return result.stdout.splitlines()  # Windows' text mode writes \r\n


def external_profile(fmus, platform: str, version: int) -> Run:
    run = Run(fmus, platform, version)
    chip = run.fmu("chip")
    run.set(chip, "script", run.path(EXAMPLES / "two_axis.script"))
    for n in (1, 2):
        run.out(chip, f"axis{n}.commandedPosition", f"axis{n}.position", f"axis{n}.velocity", f"axis{n}.acceleration")
    run.out(chip, "chipTime")
    return run


def closed_loop(fmus, platform: str, version: int) -> Run:
    run = Run(fmus, platform, version)
    chip, plant = run.fmu("chip"), run.fmu("plant")
    run.set(chip, "script", run.path(EXAMPLES / "systems" / "move.script"))
    run.set(chip, "loopback", "0")
    run.wire(chip, "axis1.motorCommand", plant, "motorCommand")
    run.wire(plant, "encoderCount", chip, "axis1.actualPosition")
    run.out(chip, "chipTime", "axis1.commandedPosition", "axis1.motorCommand", "axis1.motorOutput")
    run.out(plant, "encoderCount", "angle", "speed", "current")
    return run


CASES = [
    pytest.param(platform, version, marks=pytest.mark.skipif(bool(missing(platform)), reason=str(missing(platform))))
    for platform in PLATFORMS
    for version in (2, 3)
    if version == 3 or PLATFORMS[platform][3]
]


def column(rows: list[str], i: int) -> list[str]:
    return [row.split()[i] for row in rows]


@pytest.mark.parametrize("platform, version", CASES)
def test_the_external_profile_example_gives_the_linux64_rows_bit_for_bit(fmus, masters, wine_prefix, platform, version):
    native = external_profile(fmus, "native", version).rows(masters, STEPS_PROFILE, wine_prefix)
    assert len(native) == STEPS_PROFILE + 1
    assert len(set(column(native, 1))) > 100 and len(set(column(native, 5))) > 100, "the profile did not move"
    rows = external_profile(fmus, platform, version).rows(masters, STEPS_PROFILE, wine_prefix)
    differing = [(a, b) for a, b in zip(native, rows) if a != b]
    assert rows == native, f"{len(differing)} rows differ, the first: linux64 {differing[:1]}"


@pytest.mark.parametrize("platform, version", CASES)
def test_the_closed_loop_with_the_plant_gives_the_linux64_rows_bit_for_bit(
    fmus, masters, wine_prefix, platform, version
):
    native = closed_loop(fmus, "native", version).rows(masters, STEPS_LOOP, wine_prefix)
    encoder = [int(x) for x in column(native, 5)]
    assert encoder[-1] > 1000 and len(set(column(native, 3))) > 10, "the plant did not follow the move"
    rows = closed_loop(fmus, platform, version).rows(masters, STEPS_LOOP, wine_prefix)
    differing = [(a, b) for a, b in zip(native, rows) if a != b]
    assert rows == native, f"{len(differing)} rows differ, the first: linux64 {differing[:1]}"


def test_the_fmus_carry_each_platforms_binaries_in_its_fmi_folder(fmus):
    """FMI 2 names folders for x86 only: aarch64-linux is in the FMI 3 FMUs alone."""
    folders2 = {"linux64"} | {PLATFORMS[p][3] for p in AVAILABLE if PLATFORMS[p][3]}
    folders3 = {"x86_64-linux"} | {PLATFORMS[p][4] for p in AVAILABLE}
    for model, identifier in (("chip", "PMDMotionProcessor"), ("plant", "pmdplant")):
        for version, folders in ((2, folders2), (3, folders3)):
            binaries = fmus[model, version] / "binaries"
            carried = {p.name: sorted(f.name for f in p.iterdir()) for p in binaries.iterdir()}
            expected = {folder: [identifier + (".dll" if "win" in folder else ".so")] for folder in sorted(folders)}
            assert carried == expected, f"{identifier}-fmi{version}.fmu"


def exports_and_imports(library: Path) -> tuple[set[str], set[str]]:
    """A DLL's exported names and the DLLs it loads (objdump's PE headers)."""
    text = subprocess.run(
        ["x86_64-w64-mingw32-objdump", "-p", str(library)], capture_output=True, text=True, check=True
    ).stdout
    imports = {line.split(":", 1)[1].strip() for line in text.splitlines() if "DLL Name:" in line}
    table = text[text.index("[Ordinal/Name Pointer] Table") :].split("\n\n")[0].splitlines()[1:]
    return {line.split()[-1] for line in table if line.strip()}, imports


# the chip's documented functions beside the FMI ones (docs/architecture.md): record.data for FMI 2, which has
# no Binary type, and the memory the caller lends for its rows
CHIP_EXTENSIONS = {2: {"pmdfmu_fmi2GetRecordData", "pmdfmu_fmi2SetRecordBuffer"}, 3: {"pmdfmu_fmi3SetRecordBuffer"}}


@pytest.mark.skipif(bool(missing("x86_64-windows")), reason=str(missing("x86_64-windows")))
def test_the_windows_dlls_export_only_fmi_and_need_only_windows_own_dlls(fmus):
    for (model, version), folder in fmus.items():
        platform = "win64" if version == 2 else "x86_64-windows"
        library = next((folder / "binaries" / platform).glob("*.dll"))
        exports, imports = exports_and_imports(library)
        allowed = CHIP_EXTENSIONS[version] if model == "chip" else set()
        assert {e for e in exports if not e.startswith(f"fmi{version}")} == allowed, library
        assert {e.lower() for e in imports} <= {"kernel32.dll", "msvcrt.dll"}, f"{library} loads {imports}"


@pytest.mark.skipif(bool(missing("aarch64-linux")), reason=str(missing("aarch64-linux")))
def test_the_aarch64_libraries_export_only_fmi3(fmus):
    for model in ("chip", "plant"):
        library = next((fmus[model, 3] / "binaries" / "aarch64-linux").glob("*.so"))
        text = subprocess.run(
            ["aarch64-linux-gnu-nm", "-D", "--defined-only", str(library)], capture_output=True, text=True, check=True
        ).stdout
        names = {line.split()[-1] for line in text.splitlines() if line.split()[1] in "TDBR"}
        extensions = CHIP_EXTENSIONS[3] if model == "chip" else set()
        assert extensions <= names, library
        names -= extensions
        assert names and all(n.startswith("fmi3") for n in names), sorted(names)


def macos_recipe() -> str:
    """docs/tools.md's macOS recipe: the Python block of its macOS section."""
    text = (REPO / "docs" / "tools.md").read_text()
    section = text[text.index("### macOS") :]
    return re.search(r"```python\n(.*?)```", section, re.S).group(1)


@pytest.mark.skipif(not shutil.which("cmake"), reason="cmake not installed")
@pytest.mark.parametrize("model, version", [("chip", 3), ("plant", 2)])
def test_the_macos_recipe_builds_a_binary_from_the_sources_that_runs_as_the_shipped_one(tmp_path, model, version):
    """The recipe runs here as on the Mac: on an FMU without binaries it builds this machine's."""
    shipped = pmdfmu.default_fmu(version)
    if model == "plant":
        shipped = shipped.with_name(f"pmdplant-fmi{version}.fmu")
    bare = tmp_path / "bare.fmu"
    with zipfile.ZipFile(shipped) as z, zipfile.ZipFile(bare, "w", zipfile.ZIP_DEFLATED) as out:
        for item in z.infolist():
            if not item.filename.startswith("binaries/"):
                out.writestr(item, z.read(item))
    (tmp_path / "add_binary.py").write_text(macos_recipe())
    rebuilt = tmp_path / "rebuilt.fmu"
    subprocess.run(
        [sys.executable, "add_binary.py", str(bare), str(rebuilt)], cwd=tmp_path, check=True, capture_output=True
    )
    binaries = [n for n in zipfile.ZipFile(rebuilt).namelist() if n.startswith("binaries/") and n[-1] != "/"]
    assert len(binaries) == 1, binaries
    options = dict(stop_time=0.03, output_interval=1e-4)
    if model == "chip":
        options["start_values"] = {"script": str(EXAMPLES / "two_axis.script")}
    expected = fmpy.simulate_fmu(str(shipped), **options)
    actual = fmpy.simulate_fmu(str(rebuilt), **options)
    assert expected.dtype.names == actual.dtype.names and len(actual) > 100
    for name in expected.dtype.names:
        assert np.array_equal(expected[name], actual[name]), name
