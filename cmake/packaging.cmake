# Installation (`cmake --install build --prefix DIR`) and the Debian package (`cpack -G DEB` in
# the build folder; tools/package makes a Release build for any x86-64 in build-package/ and
# packages it). docs/install.md is the user's page for all of this.
#
# Layout under the prefix:
#   bin/rad -> ../lib/rad/rad        the program (a relative link; the real file is private)
#   bin/rad-gen                      the scene generator
#   lib/rad/web -> ../../share/rad/web
#   share/rad/web/node_modules/...   three.js and lil-gui, the modules of rad serve's page
#   share/rad/scenes/                the bundled scenes (with their OFF files)
#   share/man/man1/rad.1.gz, rad-gen.1.gz  the manual pages (docs/*.1, the project version in)
#   share/doc/rad/                   README.md, ARCHITECTURE.md and docs/ (pages and pictures)
#
# rad serve's page is compiled into rad; the three.js and lil-gui modules it hands to the browser
# are read at run time from web/node_modules beside the rad executable (the file itself, links
# followed: src/serve/web_assets.cpp). So the executable lives in lib/rad/ with web/ beside it,
# and bin/rad links to it: an installed rad serve works offline with no setting.
include(GNUInstallDirs)

set(rad_private_dir lib/rad)
set(rad_data_dir ${CMAKE_INSTALL_DATADIR}/rad)
set(rad_doc_dir ${CMAKE_INSTALL_DATADIR}/doc/rad)
set(rad_man_dir ${CMAKE_INSTALL_MANDIR}/man1)
# Directories 0755 whatever the umask (a Debian package wants them so).
set(CMAKE_INSTALL_DEFAULT_DIRECTORY_PERMISSIONS OWNER_READ OWNER_WRITE OWNER_EXECUTE GROUP_READ
                                                GROUP_EXECUTE WORLD_READ WORLD_EXECUTE)

# The programs.
install(TARGETS rad RUNTIME DESTINATION ${rad_private_dir})
install(TARGETS rad-gen RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})

# The two relative links, made in the build folder and installed as links.
set(rad_links ${PROJECT_BINARY_DIR}/install-links)
file(MAKE_DIRECTORY ${rad_links})
file(RELATIVE_PATH rad_exe_link /${CMAKE_INSTALL_BINDIR} /${rad_private_dir}/rad)
file(RELATIVE_PATH rad_web_link /${rad_private_dir} /${rad_data_dir}/web)
file(CREATE_LINK ${rad_exe_link} ${rad_links}/rad SYMBOLIC)
file(CREATE_LINK ${rad_web_link} ${rad_links}/web SYMBOLIC)
install(FILES ${rad_links}/rad DESTINATION ${CMAKE_INSTALL_BINDIR})
install(FILES ${rad_links}/web DESTINATION ${rad_private_dir})

# rad serve's page modules: only the files rad serves, with their licences and package.json
# (name and version). They come from npm (tools/setup.sh: rad_install_web) into
# build/web/node_modules; without them the install goes on, warns, and rad serve says what is
# missing when started.
set(RAD_WEB_MODULES_DIR ${PROJECT_BINARY_DIR}/web/node_modules
    CACHE PATH "node_modules folder holding three and lil-gui, installed with rad")
set(rad_web_files
    three/build/three.module.js three/build/three.core.js
    three/examples/jsm/controls/OrbitControls.js three/LICENSE three/package.json
    lil-gui/dist/lil-gui.esm.min.js lil-gui/LICENSE.md lil-gui/package.json)
foreach(f ${rad_web_files})
  get_filename_component(dir ${f} DIRECTORY)
  install(FILES ${RAD_WEB_MODULES_DIR}/${f} DESTINATION ${rad_data_dir}/web/node_modules/${dir}
          OPTIONAL)
endforeach()
install(CODE "
  if(NOT EXISTS \"${RAD_WEB_MODULES_DIR}/three/build/three.module.js\" OR
     NOT EXISTS \"${RAD_WEB_MODULES_DIR}/lil-gui/dist/lil-gui.esm.min.js\")
    message(WARNING \"rad serve's page modules (three.js, lil-gui) are not in \"
                    \"${RAD_WEB_MODULES_DIR}: the installed rad serve will have no page. \"
                    \"Install them with: bash -c 'source tools/setup.sh && rad_install_web page'\")
  endif()")

# The bundled scenes (not the malformed ones of scenes/bad, nor the reference renderer's data).
install(DIRECTORY ${PROJECT_SOURCE_DIR}/scenes/ DESTINATION ${rad_data_dir}/scenes
        PATTERN bad EXCLUDE PATTERN reference EXCLUDE)

# The manual pages, rad(1) and rad-gen(1): docs/NAME.1 with the project version (the one
# `rad --version` prints) written into its .TH line, compressed as Debian keeps manual pages.
# Made when CMake configures, and again whenever a page changes.
find_program(RAD_GZIP gzip)
foreach(rad_page rad rad-gen)
  set(rad_man_source ${PROJECT_SOURCE_DIR}/docs/${rad_page}.1)
  set(rad_man_made ${PROJECT_BINARY_DIR}/man/${rad_page}.1)
  set_property(DIRECTORY APPEND PROPERTY CMAKE_CONFIGURE_DEPENDS ${rad_man_source})
  file(READ ${rad_man_source} rad_man_text)
  string(REGEX REPLACE "\n\\.TH ([^ ]+) 1 \"([^\"]*)\" \"rad [^\"]*\""
         "\n.TH \\1 1 \"\\2\" \"rad ${PROJECT_VERSION}\"" rad_man_text "${rad_man_text}")
  file(WRITE ${rad_man_made}.new "${rad_man_text}")
  file(COPY_FILE ${rad_man_made}.new ${rad_man_made} ONLY_IF_DIFFERENT)
  if(RAD_GZIP)
    execute_process(COMMAND ${RAD_GZIP} -9nf -k ${rad_man_made} RESULT_VARIABLE rad_gzip_status)
    if(NOT rad_gzip_status EQUAL 0)
      message(FATAL_ERROR "gzip ${rad_man_made} failed")
    endif()
    install(FILES ${rad_man_made}.gz DESTINATION ${rad_man_dir})
  else()
    install(FILES ${rad_man_made} DESTINATION ${rad_man_dir})
  endif()
endforeach()

# Documentation: the README and the pages it links, as they sit in the source tree.
install(FILES ${PROJECT_SOURCE_DIR}/README.md ${PROJECT_SOURCE_DIR}/ARCHITECTURE.md
        DESTINATION ${rad_doc_dir})
install(DIRECTORY ${PROJECT_SOURCE_DIR}/docs/ DESTINATION ${rad_doc_dir}/docs
        FILES_MATCHING PATTERN "*.md" PATTERN "*.png")

# The Debian package. Its version is the project version, the one `rad --version` prints.
set(RAD_PACKAGE_MAINTAINER
    "rad maintainers <maintainers@users.noreply.h-seed-1ecf6c53.example>"
    CACHE STRING "Maintainer field of the Debian package")
set(CPACK_PACKAGE_NAME rad)
set(CPACK_PACKAGE_VENDOR "rad maintainers")
set(CPACK_PACKAGE_CONTACT ${RAD_PACKAGE_MAINTAINER})
set(CPACK_PACKAGE_DESCRIPTION_SUMMARY
    "progressive radiosity renderer with ray-traced form factors")
set(CPACK_GENERATOR DEB)
set(CPACK_PACKAGING_INSTALL_PREFIX /usr)
set(CPACK_STRIP_FILES ON)
set(CPACK_DEBIAN_FILE_NAME DEB-DEFAULT)  # rad_VERSION_ARCH.deb
set(CPACK_DEBIAN_PACKAGE_MAINTAINER ${RAD_PACKAGE_MAINTAINER})
set(CPACK_DEBIAN_PACKAGE_SECTION graphics)
set(CPACK_DEBIAN_PACKAGE_PRIORITY optional)
# The long description (CPack puts the summary first and formats the lines for Debian).
set(CPACK_PACKAGE_DESCRIPTION
    "rad computes diffuse interreflection (radiosity) in scenes made of triangles
and writes the light at every vertex. It shoots light from surface to surface
by progressive refinement, computes vertex-to-source form factors with shadow
rays, and subdivides triangles where the lighting changes.

Scenes are rad's own descriptions or OBJ, glTF and PLY models; results are
coloured meshes (PLY, OBJ, glTF, OFF), images (PNG, HDR, EXR, PFM) and
statistics. rad solves one scene, batches of scenes (Slurm job arrays), one
scene over MPI ranks, or one scene interactively in a web browser.")
# Depends: the shared libraries the programs link, as dpkg-shlibdeps (dpkg-dev) names them.
# Without it, the Debian 12 packages by hand.
find_program(RAD_DPKG_SHLIBDEPS dpkg-shlibdeps)
if(RAD_DPKG_SHLIBDEPS)
  set(CPACK_DEBIAN_PACKAGE_SHLIBDEPS ON)
else()
  set(rad_depends libembree3-3 libtbb12 libfmt9 libstb0 libtinyexr1d libtinygltf2d
                  libcpp-httplib0.11 libc6 libstdc++6 libgcc-s1)
  if(RAD_HAVE_MPI)
    list(APPEND rad_depends libopenmpi3)
  endif()
  list(JOIN rad_depends ", " CPACK_DEBIAN_PACKAGE_DEPENDS)
endif()
if(RAD_HAVE_MPI)
  # mpirun, to spread one scene over processes; rad itself runs without it.
  set(CPACK_DEBIAN_PACKAGE_SUGGESTS openmpi-bin)
endif()
include(CPack)
