"""Every CraterKit proxy: XML defaults equal C++ defaults, names match labels, docs exist.

The C++ defaults come from a fresh instance of the proxy's VTK class (NewInstance), whose
PrintSelf prints one "Name: value" line per property.
Usage: scripts/pvbatch tests/pvbatch/test_proxies.py SOURCE_DIR
"""

import glob
import os
import sys
import xml.etree.ElementTree as ET

from craterkit import load_plugin
from craterkit.testing import Checker

simple = load_plugin()
t = Checker("test_proxies")
source_dir = sys.argv[1]
xml_files = sorted(glob.glob(os.path.join(source_dir, "Plugin", "xml", "*.xml")))
t.check(len(xml_files) > 0, "no XML files found")


def printed_values(obj):
    values = {}
    for line in str(obj).splitlines():
        key, sep, value = line.strip().partition(":")
        if sep:
            values[key] = value.strip()
    return values


def same(xml_text, cpp_text):
    xs, cs = xml_text.split(), cpp_text.split()
    if len(xs) != len(cs):
        return False
    for x, c in zip(xs, cs):
        try:
            a, b = float(x), float(c)
        except ValueError:
            if x != c:
                return False
            continue
        if abs(a - b) > 1e-5 * max(abs(a), abs(b), 1e-300):
            return False
    return True


proxies = 0
bed_for_inputs = None
for path in xml_files:
    for group in ET.parse(path).getroot().findall("ProxyGroup"):
        # Readers wrapped in ParaView's file-series reader, their internal core proxies and
        # the file writers need a file to exist: test_particle_files.py covers them. The deck
        # writer carries DEMIntegrator's properties, whose defaults are checked here too.
        if group.get("name") not in ("sources", "filters", "writers"):
            continue
        for element in group:
            if element.get("class") == "vtkFileSeriesReader":
                continue
            if group.get("name") == "writers" and element.get("name") != "LAMMPSDeckWriter":
                continue
            name = element.get("name")
            label = element.get("label") or name
            proxies += 1
            t.check(label.replace(" ", "") == name,
                    f"{name}: label '{label}' does not give the name without spaces")
            doc = element.find("Documentation")
            t.check(doc is not None and (doc.text or "").strip(), f"{name}: no documentation")
            ctor = getattr(simple, name, None)
            t.check(ctor is not None, f"{name}: paraview.simple has no {name}()")
            if ctor is None:
                continue
            kwargs = {}
            if element.find("InputProperty") is not None:
                bed_for_inputs = bed_for_inputs or simple.GranularBed(ContainerRadius=3.0)
                kwargs["Input"] = bed_for_inputs
            proxy = ctor(**kwargs)
            fresh = proxy.GetClientSideObject().NewInstance()
            cpp = printed_values(fresh)
            for prop in element:
                if not prop.tag.endswith("VectorProperty") or prop.get("information_only") == "1":
                    continue
                pname = prop.get("name")
                plabel = prop.get("label") or pname
                t.check(plabel.replace(" ", "") == pname,
                        f"{name}.{pname}: label '{plabel}' does not give the name")
                t.check(hasattr(proxy, pname), f"{name}: proxy has no attribute {pname}")
                pdoc = prop.find("Documentation")
                t.check(pdoc is not None and len((pdoc.text or "").strip()) > 20,
                        f"{name}.{pname}: missing or too short documentation")
                default = prop.get("default_values")
                if default is None:
                    continue
                t.check(pname in cpp, f"{name}.{pname}: not printed by the C++ PrintSelf")
                if pname in cpp:
                    t.check(same(default, cpp[pname]),
                            f"{name}.{pname}: XML default '{default}' != C++ default '{cpp[pname]}'")
t.check(proxies >= 1, "no proxies found")
print(f"checked {proxies} proxies", flush=True)
sys.exit(t.close())
