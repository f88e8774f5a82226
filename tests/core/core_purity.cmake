cmake_minimum_required(VERSION 3.22)
# The core is pure (STYLE.md pattern 1): no source or header of vmass_core includes a thread,
# clock, file, socket or logging header, or another vmass module. Run with
#   cmake -DDIRS="dir1;dir2" -P core_purity.cmake
# and fails naming file:line and the header.
set(forbidden
  # threads
  thread mutex shared_mutex condition_variable future atomic semaphore latch barrier stop_token
  pthread.h threads.h
  # clocks
  chrono ctime time.h sys/time.h sys/timerfd.h
  # files and streams
  fstream cstdio stdio.h filesystem iostream fcntl.h unistd.h sys/stat.h sys/mman.h
  # sockets and devices
  sys/socket.h sys/ioctl.h poll.h sys/epoll.h sys/select.h netinet/in.h arpa/inet.h net/if.h
  linux/can.h
  # logging and frameworks
  syslog.h spdlog/spdlog.h systemd/sd-daemon.h)
set(findings "")
set(checked 0)
foreach(dir ${DIRS})
  file(GLOB files ${dir}/*.cpp ${dir}/*.hpp ${dir}/*.cpp.txt)
  foreach(file ${files})
    math(EXPR checked "${checked} + 1")
    file(STRINGS ${file} lines)
    set(number 0)
    foreach(line IN LISTS lines)
      math(EXPR number "${number} + 1")
      if(line MATCHES "^[ \t]*#[ \t]*include[ \t]*[<\"]([^>\"]+)[>\"]")
        set(header ${CMAKE_MATCH_1})
        if(header IN_LIST forbidden OR header MATCHES "^(spdlog|lcm|yaml-cpp|systemd|linux)/")
          string(APPEND findings "${file}:${number}: includes <${header}>\n")
        elseif(header MATCHES "^vmass/" AND NOT header MATCHES "^vmass/core/")
          string(APPEND findings "${file}:${number}: includes ${header}: the core depends on no other module\n")
        endif()
      endif()
    endforeach()
  endforeach()
endforeach()
if(checked EQUAL 0)
  message(FATAL_ERROR "core purity: no source found in ${DIRS}")
endif()
if(findings)
  message("${findings}")  # unwrapped, one finding per line
  message(FATAL_ERROR "core purity: the includes above are not allowed in the pure core (no "
    "thread, clock, file, socket or logging header, no other vmass module)")
endif()
message("core purity: ${checked} files include nothing impure")
