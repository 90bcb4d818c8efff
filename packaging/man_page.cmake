# One man page from a program's --help, by help2man, at build time:
#   cmake -DHELP2MAN=... -DPROGRAM=build/bin/launch -DPAGE=lcm-control-launch -DINVOCATION="lcm-control launch"
#         -DPURPOSE="..." -DVERSION=0.1.0 -DSEE_ALSO="lcm-control(1)" (comma-separated) -DOUTPUT=.../lcm-control-launch.1 -P man_page.cmake
# The page is named and synopsised as the installed command (lcm-control launch); its text is the program's --help.
get_filename_component(name ${PROGRAM} NAME)
set(include_file ${OUTPUT}.h2m)
string(REGEX REPLACE "([^,]+)\\(([0-9])\\)" ".BR \\1 (\\2)" see_also "${SEE_ALSO}")  # a(1),b(1): .BR a (1),\n.BR b (1)
string(REPLACE ")," "),\n" see_also "${see_also}")
string(REPLACE "-" "\\-" page_name "${PAGE}")
set(where "")
if(NOT INVOCATION STREQUAL name)
  set(where "[<DESCRIPTION]\nInstalled, this program runs as \\fB${INVOCATION}\\fR; in a build tree it is build/bin/${name}.\n")
endif()
file(WRITE ${include_file} "[NAME]\n${page_name} \\- ${PURPOSE}\n${where}[SEE ALSO]\n${see_also}\n")
execute_process(COMMAND ${HELP2MAN} --no-info --no-discard-stderr --version-string=${VERSION} "--source=lcm_control ${VERSION}"
                        --include=${include_file} --output=${OUTPUT}.tmp ${PROGRAM}
                RESULT_VARIABLE rc ERROR_VARIABLE err)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "help2man ${PROGRAM}: ${err}")
endif()
file(READ ${OUTPUT}.tmp page)
# SYNOPSIS: the command as installed; examples: one per line, as --help prints them.
string(REPLACE "\n.B ${name}\n" "\n.B ${INVOCATION}\n" page "${page}")
string(REGEX REPLACE "(Examples?:\n)\\.IP\n([^.][^\n]*\n)+" "\\0.fi\n" page "${page}")
string(REPLACE "Example:\n.IP\n" "Example:\n.IP\n.nf\n" page "${page}")
string(REPLACE "Examples:\n.IP\n" "Examples:\n.IP\n.nf\n" page "${page}")
file(WRITE ${OUTPUT} "${page}")
file(REMOVE ${OUTPUT}.tmp ${include_file})
