# Played by the real ParaView client (see run_gui_test.sh): the plugin was loaded by the GUI
# at start-up; create every CraterKit source and record what happened in a marker file.
import os

from paraview import servermanager
from paraview.simple import *  # noqa: F401,F403  (the GUI's own namespace)

marker = os.environ["CRATERKIT_GUI_MARKER"]
lines = []
try:
  pxm = servermanager.ProxyManager()
  proto = pxm.SMProxyManager.GetPrototypeProxy("sources", "GranularBed")
  lines.append("prototype %s" % ("yes" if proto is not None else "no"))
  bed = GranularBed(ContainerRadius=3.0)  # noqa: F405
  Show(bed)  # noqa: F405
  Render()  # noqa: F405
  lines.append("points %d" % bed.GetDataInformation().GetNumberOfPoints())
except Exception as error:  # recorded for run_gui_test.sh to print
  import traceback
  lines.append("error " + traceback.format_exc().replace("\n", " | "))
with open(marker, "w") as f:
  f.write("\n".join(lines) + "\n")
# --script has no "exit when done": leave the GUI once the marker is written.
os._exit(0)
