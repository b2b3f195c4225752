# Fails when app/, widgets/ or core/ cast a robot with dynamic_cast (issue 24 item 5): what the
# GUI needs to know about a robot is a capability of irgs::Robot (simulationControl(),
# simulatedWorld(), motionControl(), remoteRobot(), ...), never its concrete type. comms/ is
# where the remote robots live and may look at its own types. A cast counts when its target
# type names a robot (Robot, SimulatedRobot, LinkedRobotHandle, ArcosRobot, any *Robot*) or its
# operand is a robot (session_.robot(), robot_, ...); casts of other objects (a Behaviour, a
# JSON exception) are not this rule's business.
#   cmake -DROOT=<tree> -P check_robot_casts.cmake

set(cast "(dynamic_cast|dynamic_pointer_cast) *<")
set(robot_target "${cast} *(const +)?[A-Za-z0-9_:]*Robot[A-Za-z0-9_]* *[*&>]")
set(robot_operand "${cast}[^>]*> *\\([^)]*[Rr]obot")

set(errors "")
foreach(folder app widgets core)
  file(GLOB_RECURSE files "${ROOT}/${folder}/*.hpp" "${ROOT}/${folder}/*.cpp"
       "${ROOT}/${folder}/*.h")
  foreach(f IN LISTS files)
    # Lines by hand: file(STRINGS) would split a line at each ';' and lose the numbering.
    file(READ "${f}" content)
    string(REPLACE ";" "<semicolon>" content "${content}")
    string(REPLACE "\n" ";" lines "${content}")
    set(number 0)
    foreach(line IN LISTS lines)
      math(EXPR number "${number} + 1")
      if(line MATCHES "${robot_target}" OR line MATCHES "${robot_operand}")
        string(STRIP "${line}" line)
        string(REPLACE "<semicolon>" "" line "${line}")
        list(APPEND errors "${f}:${number}: ${line}")
      endif()
    endforeach()
  endforeach()
endforeach()

if(errors)
  list(LENGTH errors count)
  string(REPLACE ";" "\n" text "${errors}")
  message(FATAL_ERROR "${count} dynamic_cast(s) on a robot outside comms/ (use a capability of "
                      "irgs::Robot instead, docs/decisions/robot-capabilities.md):\n${text}")
endif()
message(STATUS "no dynamic_cast on a robot in app/, widgets/ or core/")
