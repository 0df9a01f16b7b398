# Writes the version stamp (cmake/version.cpp.in) at build time: the project version and
# the commit of the source tree, with ", dirty" when tracked files differ from it. Run on
# every build by the ldm_version_stamp target; OUT is rewritten only when its text changes,
# so an unchanged tree recompiles nothing and a new commit recompiles this one file (and
# relinks), never the library. Without git or .git (a source tarball) the commit is
# "unknown".
#   cmake -DSOURCE=<source dir> -DIN=<version.cpp.in> -DOUT=<version.cpp> -DPROJECT_VERSION=x.y.z -P VersionStamp.cmake
set(LDM_GIT_COMMIT unknown)
set(LDM_GIT_DIRTY false)
find_program(GIT_EXECUTABLE git)
if(GIT_EXECUTABLE AND EXISTS "${SOURCE}/.git")
  execute_process(COMMAND "${GIT_EXECUTABLE}" rev-parse --short=12 HEAD
                  WORKING_DIRECTORY "${SOURCE}" RESULT_VARIABLE failed
                  OUTPUT_VARIABLE commit OUTPUT_STRIP_TRAILING_WHITESPACE ERROR_QUIET)
  if(NOT failed AND commit)
    set(LDM_GIT_COMMIT "${commit}")
    # --no-optional-locks: a build must not take the index lock from a git command the user
    # runs at the same time; untracked files (build folders, scratch) do not count.
    execute_process(COMMAND "${GIT_EXECUTABLE}" --no-optional-locks status --porcelain
                            --untracked-files=no
                    WORKING_DIRECTORY "${SOURCE}" RESULT_VARIABLE failed
                    OUTPUT_VARIABLE changes ERROR_QUIET)
    if(NOT failed AND changes)
      set(LDM_GIT_DIRTY true)
    endif()
  endif()
endif()
configure_file("${IN}" "${OUT}.new" @ONLY)
file(COPY_FILE "${OUT}.new" "${OUT}" ONLY_IF_DIFFERENT)
file(REMOVE "${OUT}.new")
