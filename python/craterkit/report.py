"""Reports written by the examples: report.json (machine-readable, full precision) and report.md
(for people: numbers rounded to what they mean, what the run is, and where validation stands)."""

import json
import os


def rounded(value, digits=3):
    """VALUE to DIGITS significant figures, without an exponent (0.8346110545424051 -> '0.835',
    1234.5 -> '1230'); other types unchanged."""
    if isinstance(value, bool) or not isinstance(value, float):
        return value
    import numpy as np
    return np.format_float_positional(value, precision=digits, unique=False, fractional=False, trim="-")


def validation_summary(path):
    """The rows of the validation table (tests/slow/validate.py) at PATH as markdown, with the
    sentence that says when they were run; or a sentence saying that none has been run."""
    if not os.path.exists(path):
        return ("No validation case has been run on this machine yet (`scripts/test -L slow` runs them "
                "and writes results/validation.md; docs/validation.md holds the recorded results).\n")
    with open(path) as f:
        rows = [line for line in f if line.startswith("|")]
    dates = sorted({cells[7].strip() for cells in (r.strip().strip("|").split("|") for r in rows[2:])
                    if len(cells) > 7})
    when = f"run {dates[0]}" + (f" to {dates[-1]}" if len(dates) > 1 else "") if dates else "not dated"
    return f"Latest validation results ({when}; from {path}):\n\n" + "".join(rows)


def write_report(output_dir, title, image, report, about="", validation=""):
    """Writes report.json with every entry and report.md with ABOUT (what the run is), the picture,
    the scalar entries rounded to three significant figures, and VALIDATION."""
    with open(os.path.join(output_dir, "report.json"), "w") as f:
        json.dump(report, f, indent=2)
    with open(os.path.join(output_dir, "report.md"), "w") as f:
        f.write(f"# CraterKit: {title}\n\n")
        if about:
            f.write(about.strip() + "\n\n")
        f.write(f"![{title}]({image})\n\n| quantity | value |\n|---|---|\n")
        for key, value in report.items():
            if not isinstance(value, (list, dict)):
                f.write(f"| {key} | {rounded(value)} |\n")
        if validation:
            f.write("\n## Validation\n\n" + validation.strip() + "\n")
