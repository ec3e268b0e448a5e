"""Reports written by the examples: report.json (machine-readable) and report.md."""

import json
import os


def write_report(output_dir, title, image, report):
    """Writes report.json with every entry and report.md with the picture and the scalar ones."""
    with open(os.path.join(output_dir, "report.json"), "w") as f:
        json.dump(report, f, indent=2)
    with open(os.path.join(output_dir, "report.md"), "w") as f:
        f.write(f"# CraterKit: {title}\n\n![{title}]({image})\n\n| quantity | value |\n|---|---|\n")
        for key, value in report.items():
            if not isinstance(value, (list, dict)):
                f.write(f"| {key} | {value} |\n")
