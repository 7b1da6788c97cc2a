# SPDX-License-Identifier: MIT
"""ropesim run --junit: the report parses with xml.etree and holds one test case per check, with a
<failure> for each failed check and the worst value, bound and time in every case's <system-out>.

usage: junit_report_check.py ROPESIM WORK_DIR
"""
import json
import os
import subprocess
import sys
import xml.etree.ElementTree as ET

ropesim, work = sys.argv[1], sys.argv[2]
os.makedirs(work, exist_ok=True)
scene = {
    "duration": 0.5,
    "bodies": [{"name": "ball", "shape": "sphere", "radius": 0.1, "motion": "dynamic", "mass": 1.0,
                "position": [0, 2, 0]}],
    "checks": [
        {"name": "ball falls below 2 m", "type": "position", "body": "ball", "at": 0.5,
         "box": {"min": [-1, 0, -1], "max": [1, 2, 1]}},
        {"name": "ball stays near the start", "type": "position", "body": "ball", "target": [0, 2, 0], "max": 0.5,
         "to": 0.2},
        {"name": "ball <never> leaves 1 cm & more", "type": "position", "body": "ball", "target": [0, 2, 0], "max": 0.01},
    ],
}
scene_file = os.path.join(work, "junit_scene.json")
report = os.path.join(work, "junit_report.xml")
with open(scene_file, "w") as f:
    json.dump(scene, f)
if os.path.exists(report):
    os.remove(report)
run = subprocess.run([ropesim, "run", scene_file, "--no-render", "--quiet", "--junit", report],
                     capture_output=True, text=True)
assert run.returncode == 1, (run.returncode, run.stdout, run.stderr)

root = ET.parse(report).getroot()
assert root.tag == "testsuites", root.tag
assert root.get("tests") == "3" and root.get("failures") == "1" and root.get("errors") == "0", root.attrib
suites = root.findall("testsuite")
assert len(suites) == 1 and suites[0].get("name") == "junit_scene", [s.attrib for s in suites]
cases = suites[0].findall("testcase")
assert [c.get("name") for c in cases] == [c["name"] for c in scene["checks"]], [c.get("name") for c in cases]
failed = [c for c in cases if c.find("failure") is not None]
assert [c.get("name") for c in failed] == ["ball <never> leaves 1 cm & more"], [c.get("name") for c in failed]

# Symplectic Euler from rest: the ball falls g h^2 n (n + 1) / 2 in n steps; the failing check's
# worst is the last step's distance, at 0.5 s.
h = 1.0 / 240.0
fallen = 9.81 * h * h * 120 * 121 / 2
out = failed[0].find("system-out").text
fields = dict(item.split("=", 1) for item in out.replace('bound="<= 0.01"', "bound=0.01").split())
assert abs(float(fields["worst"]) - fallen) < 1e-6, (fields, fallen)
assert abs(float(fields["time"]) - 0.5) < 1e-9, fields
assert fields["unit"] == "m", fields
assert "FAILS" in failed[0].find("failure").get("message"), failed[0].find("failure").attrib
for case in cases:
    assert case.find("system-out") is not None
print("JUnit report OK:", report)
