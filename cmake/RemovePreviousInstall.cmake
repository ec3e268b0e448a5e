# First step of `cmake --install`: removes the files that an earlier install into the same
# prefix listed in its manifest (share/craterkit/install-manifest.txt, written by
# WriteInstallManifest.cmake), so that no file of another CraterKit version stays behind
# (a module, an example or a material file that this version no longer has), and every file
# of this version is copied afresh. Python's caches beside removed modules go too.
# (A relative --prefix is relative to the working folder, as cmake --install takes it.)
get_filename_component(craterkit_prefix "${CMAKE_INSTALL_PREFIX}" ABSOLUTE)
get_filename_component(craterkit_root "$ENV{DESTDIR}${CMAKE_INSTALL_PREFIX}" ABSOLUTE)
if(NOT DEFINED CRATERKIT_MANIFEST)
  set(CRATERKIT_MANIFEST "share/craterkit/install-manifest.txt")
endif()
set(craterkit_manifest "${craterkit_root}/${CRATERKIT_MANIFEST}")
if(EXISTS "${craterkit_manifest}")
  file(STRINGS "${craterkit_manifest}" craterkit_old_files)
  set(craterkit_removed 0)
  set(craterkit_caches "")
  foreach(f IN LISTS craterkit_old_files)
    # Only what the manifest can mean: a relative path inside the prefix.
    if(f STREQUAL "" OR f MATCHES "^#" OR IS_ABSOLUTE "${f}" OR f MATCHES "(^|/)\\.\\.(/|$)")
      continue()
    endif()
    set(path "${craterkit_root}/${f}")
    if(IS_SYMLINK "${path}" OR (EXISTS "${path}" AND NOT IS_DIRECTORY "${path}"))
      file(REMOVE "${path}")
      math(EXPR craterkit_removed "${craterkit_removed} + 1")
      if(f MATCHES "\\.py$")
        get_filename_component(dir "${path}" DIRECTORY)
        list(APPEND craterkit_caches "${dir}/__pycache__")
      endif()
    endif()
  endforeach()
  list(REMOVE_DUPLICATES craterkit_caches)
  foreach(dir IN LISTS craterkit_caches)
    file(REMOVE_RECURSE "${dir}")
  endforeach()
  message(STATUS "Removed the ${craterkit_removed} files of the CraterKit installed before "
                 "(${craterkit_manifest})")
endif()
