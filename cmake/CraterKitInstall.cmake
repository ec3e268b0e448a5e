# What `cmake --install build --prefix P` puts under P, and the Debian package (cpack -G DEB,
# scripts/package), which is the same under /usr. Included by the top-level CMakeLists.txt
# after the plugin is defined. All of it is in the install component "runtime".
#
#   bin/craterkit-pvbatch                  scripts/pvbatch, finding everything relative to itself
#   bin/craterkit-run-lammps               scripts/run-lammps (craterkit.lammps runs it)
#   bin/paraview.conf                      ParaView's GUI reads it: names the plugin list below
#   lib/<multiarch>/paraview-5.11/plugins/craterkit.plugins.xml    the plugin list (no auto-load)
#   lib/<multiarch>/paraview-5.11/plugins/CraterKit/               CraterKit.so, its two module
#                                          libraries and craterkit-build.json (versions)
#   lib/python3/dist-packages/craterkit/   the Python package and its generated _version.py
#   share/craterkit/examples/, share/craterkit/materials/
#   share/craterkit/install-manifest.txt   every file installed (the next install removes them)
#   share/doc/craterkit/copyright          LICENSE
#
# Every path an installed file holds is relative to that file: the prefix can be moved.

set(CRATERKIT_INSTALL_PYTHONDIR "lib/python3/dist-packages" CACHE STRING
    "Folder of the installed Python package craterkit, relative to the prefix (Debian's layout)")
set(craterkit_py_pkg "${CRATERKIT_INSTALL_PYTHONDIR}/craterkit")
set(craterkit_plugins_dir "${CRATERKIT_INSTALL_LIBDIR}/${CRATERKIT_PARAVIEW_SUBDIR}")
set(craterkit_generated "${CMAKE_BINARY_DIR}/generated")

# Writes CONTENT to PATH unless PATH already holds it (no needless rebuilds or reinstalls).
function(craterkit_write path content)
  set(old "")
  if(EXISTS "${path}")
    file(READ "${path}" old)
  endif()
  if(NOT old STREQUAL content)
    file(WRITE "${path}" "${content}")
  endif()
endfunction()

# Relative path from folder FROM to path TO, both relative to the prefix.
function(craterkit_relative var from to)
  file(RELATIVE_PATH rel "/prefix/${from}" "/prefix/${to}")
  set(${var} "${rel}" PARENT_SCOPE)
endfunction()

# --- Beside the plugin, in the build tree and installed ---------------------------------------
# The versions the plugin was built with: craterkit.load_plugin() reads this before it loads
# the plugin and stops, naming both, when the running ParaView is not the one it was built for.
craterkit_write("${CRATERKIT_PLUGIN_DIR}/craterkit-build.json"
"{
  \"craterkit_version\": \"${PROJECT_VERSION}\",
  \"paraview_version\": \"${ParaView_VERSION_MAJOR}.${ParaView_VERSION_MINOR}\",
  \"paraview_version_full\": \"${ParaView_VERSION}\"
}
")
install(FILES "${CRATERKIT_PLUGIN_DIR}/craterkit-build.json"
        DESTINATION "${CRATERKIT_INSTALL_PLUGIN_DIR}" COMPONENT runtime)
# Build tree only: the SPH filter's material folder is the link "materials" beside the plugin
# (Filters/CMakeLists.txt); installed, it is share/craterkit/materials.
file(MAKE_DIRECTORY "${CRATERKIT_PLUGIN_DIR}")
set(craterkit_link "${CRATERKIT_PLUGIN_DIR}/materials")
if(IS_SYMLINK "${craterkit_link}")
  file(READ_SYMLINK "${craterkit_link}" craterkit_link_target)
  if(NOT craterkit_link_target STREQUAL "${PROJECT_SOURCE_DIR}/data/materials")
    file(REMOVE "${craterkit_link}")
  endif()
endif()
if(NOT IS_SYMLINK "${craterkit_link}")
  file(CREATE_LINK "${PROJECT_SOURCE_DIR}/data/materials" "${craterkit_link}" SYMBOLIC)
endif()

# --- ParaView's plugin list ------------------------------------------------------------------
# Debian's ParaView 5.11 reads no plugin list by itself: its GUI reads the files named in
# bin/paraview.conf beside the executable (one path a line, relative to that folder), and
# pvpython/pvbatch read only $PV_PLUGIN_CONFIG_FILE. The list names the plugin only: ParaView
# finds it as CraterKit/CraterKit.so beside the list (a filename= attribute is refused when
# the list's path has a "..", as the relative line in paraview.conf gives it). auto_load="0":
# Tools > Manage Plugins shows it, loading is the user's.
craterkit_write("${craterkit_generated}/craterkit.plugins.xml"
"<?xml version=\"1.0\"?>
<Plugins>
  <Plugin name=\"CraterKit\" auto_load=\"0\"/>
</Plugins>
")
install(FILES "${craterkit_generated}/craterkit.plugins.xml"
        DESTINATION "${craterkit_plugins_dir}" COMPONENT runtime)
craterkit_relative(craterkit_conf_line "${CMAKE_INSTALL_BINDIR}"
                   "${craterkit_plugins_dir}/craterkit.plugins.xml")
craterkit_write("${craterkit_generated}/paraview.conf" "${craterkit_conf_line}\n")
install(FILES "${craterkit_generated}/paraview.conf"
        DESTINATION "${CMAKE_INSTALL_BINDIR}" COMPONENT runtime)

# --- Python package --------------------------------------------------------------------------
install(DIRECTORY "${PROJECT_SOURCE_DIR}/python/craterkit/" DESTINATION "${craterkit_py_pkg}"
        COMPONENT runtime FILES_MATCHING PATTERN "*.py" PATTERN "__pycache__" EXCLUDE)
craterkit_relative(CRATERKIT_PY_PLUGIN "${craterkit_py_pkg}"
                   "${CRATERKIT_INSTALL_PLUGIN_DIR}/CraterKit.so")
craterkit_relative(CRATERKIT_PY_MATERIALS "${craterkit_py_pkg}"
                   "${CRATERKIT_INSTALL_MATERIALS_DIR}")
craterkit_relative(CRATERKIT_PY_RUN_LAMMPS "${craterkit_py_pkg}"
                   "${CMAKE_INSTALL_BINDIR}/craterkit-run-lammps")
configure_file("${PROJECT_SOURCE_DIR}/python/craterkit/_version.py.in"
               "${craterkit_generated}/python/craterkit/_version.py" @ONLY)
install(FILES "${craterkit_generated}/python/craterkit/_version.py"
        DESTINATION "${craterkit_py_pkg}" COMPONENT runtime)

# --- Scripts ---------------------------------------------------------------------------------
# craterkit-pvbatch is scripts/pvbatch with its two "installed_..._dir=" lines filled in.
set_property(DIRECTORY "${PROJECT_SOURCE_DIR}" APPEND PROPERTY CMAKE_CONFIGURE_DEPENDS
             "${PROJECT_SOURCE_DIR}/scripts/pvbatch")
file(READ "${PROJECT_SOURCE_DIR}/scripts/pvbatch" craterkit_pvbatch)
craterkit_relative(craterkit_rel_plugin "${CMAKE_INSTALL_BINDIR}" "${CRATERKIT_INSTALL_PLUGIN_DIR}")
craterkit_relative(craterkit_rel_python "${CMAKE_INSTALL_BINDIR}" "${CRATERKIT_INSTALL_PYTHONDIR}")
foreach(pair IN ITEMS "plugin;${craterkit_rel_plugin}" "python;${craterkit_rel_python}")
  list(GET pair 0 what)
  list(GET pair 1 rel)
  string(FIND "${craterkit_pvbatch}" "\ninstalled_${what}_dir=\n" at)
  if(at EQUAL -1)
    message(FATAL_ERROR "scripts/pvbatch has no line 'installed_${what}_dir=' to fill in")
  endif()
  string(REPLACE "\ninstalled_${what}_dir=\n" "\ninstalled_${what}_dir=${rel}\n"
         craterkit_pvbatch "${craterkit_pvbatch}")
endforeach()
craterkit_write("${craterkit_generated}/bin/craterkit-pvbatch" "${craterkit_pvbatch}")
install(PROGRAMS "${craterkit_generated}/bin/craterkit-pvbatch"
        DESTINATION "${CMAKE_INSTALL_BINDIR}" COMPONENT runtime)
install(PROGRAMS "${PROJECT_SOURCE_DIR}/scripts/run-lammps"
        DESTINATION "${CMAKE_INSTALL_BINDIR}" RENAME craterkit-run-lammps COMPONENT runtime)

# --- Data ------------------------------------------------------------------------------------
install(DIRECTORY "${PROJECT_SOURCE_DIR}/examples/" DESTINATION "${CMAKE_INSTALL_DATADIR}/craterkit/examples"
        COMPONENT runtime FILES_MATCHING PATTERN "*.py" PATTERN "__pycache__" EXCLUDE)
install(DIRECTORY "${PROJECT_SOURCE_DIR}/data/materials/"
        DESTINATION "${CRATERKIT_INSTALL_MATERIALS_DIR}" COMPONENT runtime
        FILES_MATCHING PATTERN "*.cfg" PATTERN "*.md")
install(FILES "${PROJECT_SOURCE_DIR}/LICENSE" DESTINATION "${CMAKE_INSTALL_DATADIR}/doc/craterkit"
        RENAME copyright COMPONENT runtime)

# --- Last: the manifest of this install ------------------------------------------------------
install(CODE "set(CRATERKIT_MANIFEST \"${CMAKE_INSTALL_DATADIR}/craterkit/install-manifest.txt\")
set(CRATERKIT_VERSION \"${PROJECT_VERSION}\")" COMPONENT runtime)
install(SCRIPT "${PROJECT_SOURCE_DIR}/cmake/WriteInstallManifest.cmake" COMPONENT runtime)

# --- The Debian package ----------------------------------------------------------------------
# cpack -G DEB in the build folder writes craterkit_<version>_<arch>.deb: the component
# "runtime" under /usr. dpkg-shlibdeps derives the library dependencies (paraview pinned to
# the 5.11.0 it was built against, libgomp1, libgmp10, zlib1g, libstdc++6, libc6, libgcc-s1);
# the others are what the Python side and headless rendering need.
# cpack (and make install) install what is built and do not build first: scripts/package
# builds, then packages; the package test packages the build under test as it is.
set(CMAKE_SKIP_INSTALL_ALL_DEPENDENCY ON)
set(CPACK_PACKAGE_NAME craterkit)
set(CPACK_PACKAGE_VERSION "${PROJECT_VERSION}")
set(CPACK_PACKAGE_VENDOR "The CraterKit developers")
set(CPACK_PACKAGE_CONTACT "The CraterKit developers")
set(CPACK_PACKAGE_DESCRIPTION_SUMMARY
    "ParaView plugin for impact cratering on small bodies (SPH, DEM, bonded DEM)")
# The first line is the synopsis; cpack indents the others.
set(CPACK_DEBIAN_PACKAGE_DESCRIPTION
    "${CPACK_PACKAGE_DESCRIPTION_SUMMARY}
CraterKit adds sources and filters to ParaView 5.11 for simulating impact cratering on
small bodies: granular beds, an SPH impact stage, a soft-sphere DEM stage and the hand-off
between them, a bonded-particle model for hypervelocity impacts and a 2D hard-disk model.
It includes the Python package craterkit, craterkit-pvbatch (pvbatch with the plugin loaded
and headless rendering) and the examples (/usr/share/craterkit/examples).")
set(CPACK_GENERATOR DEB)
set(CPACK_PACKAGING_INSTALL_PREFIX /usr)
set(CPACK_INSTALL_CMAKE_PROJECTS "${CMAKE_BINARY_DIR};${PROJECT_NAME};runtime;/")
set(CPACK_DEBIAN_FILE_NAME DEB-DEFAULT)
set(CPACK_DEBIAN_PACKAGE_SECTION science)
set(CPACK_DEBIAN_PACKAGE_PRIORITY optional)
set(CPACK_DEBIAN_PACKAGE_SHLIBDEPS ON)
set(CPACK_DEBIAN_PACKAGE_DEPENDS
    "python3-paraview, python3-numpy, python3-matplotlib, xvfb, libgl1-mesa-dri")
set(CPACK_DEBIAN_PACKAGE_RECOMMENDS "ffmpeg")
set(CPACK_DEBIAN_PACKAGE_SUGGESTS "lammps, openmpi-bin")
configure_file("${PROJECT_SOURCE_DIR}/cmake/debian/prerm.in" "${craterkit_generated}/debian/prerm"
               @ONLY)
set(CPACK_DEBIAN_PACKAGE_CONTROL_EXTRA "${craterkit_generated}/debian/prerm")
set(CPACK_DEBIAN_PACKAGE_CONTROL_STRICT_PERMISSION TRUE)
include(CPack)
