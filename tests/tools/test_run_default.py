#!/usr/bin/python3
"""tools/run-default builds only what the default job needs: the navemu binary.

The script runs in a copy of the tree whose tools/install-deps is a stand-in, with a cmake
stand-in first on PATH that records its arguments and makes a stand-in navemu in the build
folder. Checked: one configure, one build of `--target navemu` and nothing else (building every
test and fuzz target took 9 min on 2 cores), then navemu run on configs/default.yaml with the
script's arguments passed on. Exit 0 when all hold.
"""
import os
import shutil
import subprocess
import sys
import tempfile

root = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..")
with tempfile.TemporaryDirectory() as tmp:
    tree = os.path.join(tmp, "tree")
    os.makedirs(os.path.join(tree, "tools"))
    shutil.copy(os.path.join(root, "tools", "run-default"), os.path.join(tree, "tools"))
    stub = os.path.join(tree, "tools", "install-deps")
    with open(stub, "w") as f:
        f.write("#!/bin/sh\nexit 0\n")
    os.chmod(stub, 0o755)
    bin_dir, log, build = os.path.join(tmp, "bin"), os.path.join(tmp, "cmake.log"), os.path.join(tmp, "build")
    os.makedirs(bin_dir)
    with open(os.path.join(bin_dir, "cmake"), "w") as f:
        f.write(f"""#!/bin/sh
echo "$@" >> {log}
mkdir -p {build}/emulator
printf '#!/bin/sh\\necho navemu "$@"\\n' > {build}/emulator/navemu
chmod +x {build}/emulator/navemu
""")
    os.chmod(os.path.join(bin_dir, "cmake"), 0o755)
    env = dict(os.environ, PATH=bin_dir + ":" + os.environ["PATH"], NAVEMU_BUILD_DIR=build)
    r = subprocess.run([os.path.join(tree, "tools", "run-default"), "--duration", "60"], env=env,
                       capture_output=True, text=True, timeout=60)
    calls = open(log).read().splitlines() if os.path.exists(log) else []
    failures = []
    if r.returncode != 0:
        failures.append(f"exit code {r.returncode}: {r.stderr}")
    builds = [c for c in calls if c.startswith("--build")]
    if len(calls) != 2 or not calls[0].startswith("-S") or len(builds) != 1:
        failures.append(f"want one configure and one build, got: {calls}")
    elif "--target navemu" not in builds[0]:
        failures.append(f"the build is not of the navemu target alone: {builds[0]}")
    want = f"navemu run {os.path.join(tree, 'configs', 'default.yaml')} --duration 60"
    if r.stdout.strip() != want:
        failures.append(f"ran {r.stdout.strip()!r}, want {want!r}")
for f in failures:
    print("FAIL:", f)
print("run-default:", "ok" if not failures else f"{len(failures)} failures")
sys.exit(1 if failures else 0)
