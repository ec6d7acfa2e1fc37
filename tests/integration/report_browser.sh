source "$(dirname "$0")/lib.sh"
# A real browser opens a run's report page. RUN_DIR (a run of ./pbms run,
# from a fixture) must hold the report.html the run wrote at its end; the
# test rebuilds it with `./pbms report` on a copy (other tests read the
# fixture's directory meanwhile), opens it in headless Chromium (Debian's
# chromium, a test dependency that ./pbms test installs), and checks:
# - the screenshot is a PNG of the page, not blank;
# - the page's self-check ran: no image that did not decode, no script error;
# - every stage of the manifest has its section, every finished stage its
#   key numbers, and each concurrent stage that wrote particle frames the
#   picture of its body, as an <img>;
# - a failed run's page says so, with the failure's message;
# - `./pbms report` printed the page's path and a line per stage.
# The screenshot stays in the test's directory (screenshot.png).
src="${1:?usage: report_browser.sh ROOT RUN_DIR}"
command -v chromium >/dev/null ||
  fail "chromium is missing: install Debian's chromium (./pbms test installs it)"
[ -f "$src/manifest.yaml" ] || fail "no run directory at $src"
[ -s "$src/report.html" ] || fail "the run did not write $src/report.html"
rm -rf run chromium-profile
cp -r "$src" run
rm -f run/report.html run/*_body.png
start=$(date +%s.%N)
"$PBMS" report run > last_lines.txt 2> report_err.txt || { cat report_err.txt; fail "./pbms report failed"; }
echo "./pbms report took $("$PY" -c "print(round($(date +%s.%N) - $start, 2))") s:"
cat last_lines.txt

page="file://$PWD/run/report.html"
browser() {
  timeout 120 chromium --headless --no-sandbox --disable-gpu --disable-dev-shm-usage \
    --user-data-dir="$PWD/chromium-profile" --hide-scrollbars "$@" "$page" 2>>chromium.log
}
browser --screenshot="$PWD/screenshot.png" --window-size=1280,4000 > /dev/null ||
  { tail -20 chromium.log; fail "chromium could not take a screenshot"; }
browser --dump-dom --virtual-time-budget=10000 > dom.html ||
  { tail -20 chromium.log; fail "chromium could not dump the page"; }

"$PY" - run screenshot.png dom.html last_lines.txt <<'PYEOF'
import os, re, sys
from html.parser import HTMLParser
import h5py, yaml
import matplotlib
matplotlib.use("Agg")
import matplotlib.image as mpimg
import numpy as np
from checklist import Checklist

run, shot, dom_path, lines_path = sys.argv[1:5]
check = Checklist()


class Dom(HTMLParser):
    def __init__(self, text):
        super().__init__()
        self.imgs, self.ids, self.selfcheck, self.cards = [], set(), {}, 0
        self.feed(text)

    def handle_starttag(self, tag, attrs):
        a = dict(attrs)
        if tag == "img":
            self.imgs.append(a)
        if "id" in a:
            self.ids.add(a["id"])
        if a.get("id") == "pbms-selfcheck":
            self.selfcheck = a


with open(shot, "rb") as f:
    check(f.read(8) == b"\x89PNG\r\n\x1a\n", "the screenshot is a PNG")
pixels = mpimg.imread(shot)[..., :3]
grey = pixels.mean(axis=2)
inked = float(np.mean(grey < 0.9))
check(pixels.shape[:2] == (4000, 1280) and grey.std() > 0.05 and inked > 0.02,
      f"the screenshot is not blank: {pixels.shape[1]}x{pixels.shape[0]}, "
      f"{100 * inked:.1f} % of it drawn, grey spread {grey.std():.3f}")

dom_text = open(dom_path, encoding="utf-8").read()
dom = Dom(dom_text)
sc = dom.selfcheck
check(sc.get("data-checked") == "yes", f"the page's self-check ran in the browser ({sc.get('data-checked')})")
check(sc.get("data-broken-images") == "0" and int(sc.get("data-images", -1)) == len(dom.imgs),
      f"no broken image: {sc.get('data-broken-images')} of {sc.get('data-images')} did not decode")
check(sc.get("data-script-errors") == "0", f"no script error ({sc.get('data-script-errors')})")
check(all(i.get("src", "").startswith("data:image/png;base64,") for i in dom.imgs),
      f"all {len(dom.imgs)} images are inline")

manifest = yaml.safe_load(open(os.path.join(run, "manifest.yaml")))
stages = manifest.get("stages") or []
missing = [s["name"] for s in stages if f"stage-{s['name']}" not in dom.ids]
check(stages and not missing, f"every stage of the manifest has its section ({len(stages)} stages; missing {missing})")


def section(name):
    """The DOM text of one stage's section."""
    m = re.search(rf'<section class="stage" id="stage-{re.escape(name)}">(.*?)</section>', dom_text, re.S)
    return m.group(1) if m else ""


no_numbers = [s["name"] for s in stages if s.get("status") == "ok"
              and 'class="card"' not in section(s["name"])]
check(not no_numbers, f"every finished stage shows its key numbers (none in {no_numbers})")


def has_frames(stage):
    for part in ("dpd", "mpm"):
        path = os.path.join(run, stage, f"{part}_particles.h5md")
        try:
            with h5py.File(path, "r") as f:
                if f["particles/all/position/value"].shape[1] > 0:
                    return True
        except (OSError, KeyError):
            continue
    return False


bodies = [s["name"] for s in stages if s.get("kind") == "concurrent" and has_frames(s["name"])]
alts = {i.get("alt") for i in dom.imgs}
no_body = [b for b in bodies if f"{b}_body.png" not in alts]
check(not no_body, f"each concurrent stage with particle frames has its body picture "
      f"({len(bodies)}: {bodies}; missing {no_body})")
if manifest.get("status") == "failed":
    message = str((manifest.get("failure") or {}).get("message", ""))
    check("The run failed" in dom_text and message[:60] in dom_text,
          f"the failed run's page says so, with the message ({message[:60]}...)")
lines = open(lines_path, encoding="utf-8").read().splitlines()
check(bool(lines) and lines[0].startswith("pbms: report: ") and lines[0].endswith("/report.html"),
      f"./pbms report prints the page's path first ({lines[:1]})")
named = [s["name"] for s in stages if not any(ln.startswith(f"pbms:   {s['name']} (") for ln in lines)]
check(not named, f"and a line per stage (missing {named})")
sys.exit(check.finish())
PYEOF
