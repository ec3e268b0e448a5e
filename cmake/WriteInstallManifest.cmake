# Last step of `cmake --install`: writes share/craterkit/install-manifest.txt under the
# prefix, every file this install put there relative to the prefix (itself included), for the
# next install into the same prefix to remove first (RemovePreviousInstall.cmake).
# (A relative --prefix is relative to the working folder, as cmake --install takes it.)
get_filename_component(craterkit_prefix "${CMAKE_INSTALL_PREFIX}" ABSOLUTE)
get_filename_component(craterkit_root "$ENV{DESTDIR}${CMAKE_INSTALL_PREFIX}" ABSOLUTE)
if(NOT DEFINED CRATERKIT_MANIFEST)
  set(CRATERKIT_MANIFEST "share/craterkit/install-manifest.txt")
endif()
set(craterkit_files "${CRATERKIT_MANIFEST}")
foreach(f IN LISTS CMAKE_INSTALL_MANIFEST_FILES)
  # The entries are absolute, with or without DESTDIR in front.
  foreach(base IN ITEMS "${craterkit_root}" "${craterkit_prefix}")
    string(LENGTH "${base}/" n)
    string(SUBSTRING "${f}" 0 ${n} head)
    if(head STREQUAL "${base}/")
      string(SUBSTRING "${f}" ${n} -1 rel)
      list(APPEND craterkit_files "${rel}")
      break()
    endif()
  endforeach()
endforeach()
list(REMOVE_DUPLICATES craterkit_files)
list(SORT craterkit_files)
string(REPLACE ";" "\n" craterkit_lines "${craterkit_files}")
file(WRITE "${craterkit_root}/${CRATERKIT_MANIFEST}"
     "# CraterKit ${CRATERKIT_VERSION}: the files installed under this prefix, relative to it.\n"
     "# The next cmake --install into this prefix removes them before it installs.\n"
     "${craterkit_lines}\n")
list(APPEND CMAKE_INSTALL_MANIFEST_FILES "${craterkit_prefix}/${CRATERKIT_MANIFEST}")
message(STATUS "Manifest: ${craterkit_root}/${CRATERKIT_MANIFEST}")
