"""Outside check, ``velpoly html``'s results table against ``velpoly solve``'s (FORMAT.md section 3: the page's
"table updating live"). Found by the audit: the page printed rounding noise where every table of velpoly prints
0, and measured a deviation against it: a parallelogram four-bar at a constant crank speed, re-assembled at
another angle, showed alpha_3 = -1.4211e-14 (graphical) beside 7.1054e-15 (analytic), deviation 3.0e+0, where
``velpoly solve`` prints 0 and 0 (compare.kind_floor: below a billionth of the largest value of its kind,
alpha at least omega^2). The page's script now reads the same scales (kindScales) and floors; a negative
exponent's minus is typeset as the mantissa's. The script runs here in Node on a stand-in document.
"""
from __future__ import annotations

import json
import re
import shutil
import subprocess

import numpy as np
import pytest

import velpoly
from velpoly.report import solution_report

from test_audit_tables import parallelogram

NODE = shutil.which("node") or shutil.which("nodejs")

# the page's data and script run on a document that takes anything; prints the results table's HTML
HARNESS = r"""
const fs = require("fs");
const html = fs.readFileSync(process.argv[2], "utf8");
const data = html.match(/window\.VELPOLY_STATIC=[\s\S]*?;\nwindow\.VELPOLY_POSES=[\s\S]*?;\n/)[0];
const script = html.match(/\(function \(\) \{\n  "use strict";[\s\S]*\}\)\(\);/)[0];
const byId = {};
function stub(store) {
  return new Proxy(function () { return stub(); }, {
    get(t, k) {
      if (k === Symbol.toPrimitive) return () => 0;
      if (k === "length") return 0;
      return store && k in store ? store[k] : stub();
    },
    set(t, k, v) { if (store) store[k] = v; return true; },
    apply() { return stub(); },
  });
}
global.window = global;
global.document = stub({ getElementById: (id) => byId[id] || (byId[id] = stub({ id })),
                         querySelectorAll: () => [] });
global.addEventListener = () => {}; global.requestAnimationFrame = () => 0; global.setTimeout = () => 0;
global.location = stub({ hash: "" });
eval(data);
eval(script);
console.log(JSON.stringify(byId.results.innerHTML));
"""


@pytest.mark.skipif(NODE is None, reason="no Node.js to run the page's script")
def test_the_page_prints_rounding_noise_as_zero_as_solve_does(tmp_path):
    harness = tmp_path / "harness.js"
    harness.write_text(HARNESS)
    rng = np.random.default_rng(7)
    for k in range(3):   # parallelograms at a constant crank speed, the file's pose away from the drawn one
        mech = parallelogram(rng)
        mech["driver"]["angle"] = float(rng.uniform(20, 160))
        m = velpoly.load(mech)
        sol = velpoly.solve(m)
        assert any(a != 0 for a in sol.alpha.values()) or k   # noise to print (at least the first)
        lines = solution_report(sol).splitlines()
        links = lines[lines.index("Links") + 3:lines.index("Points") - 1]
        assert [row.split()[-1] for row in links] == ["0"] * 4, links
        page = tmp_path / f"p{k}.html"
        velpoly.html(m, step=30.0).save(page)
        table = json.loads(subprocess.run([NODE, str(harness), str(page)], capture_output=True, text=True,
                                          check=True, timeout=60).stdout)
        rows = re.findall(r"<tr><td><i>α</i><sub>(\w+)</sub> \(rad/s²\)</td><td>([^<]*)</td><td>([^<]*)</td><td>(.*?)</td></tr>",
                          table)
        assert [r[0] for r in rows] == ["2", "3", "4"], table
        for lk, graphical, analytic, deviation in rows:
            assert graphical == analytic == "0", (lk, graphical, analytic)
            assert deviation == "&lt; 10<sup>−12</sup>", (lk, deviation)
        assert "e-" not in table   # a negative exponent's minus is the typeset one
