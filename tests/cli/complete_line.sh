#!/usr/bin/env bash
# Completes a command line as bash would, with a completion script: sets COMP_LINE,
# COMP_POINT, COMP_WORDS and COMP_CWORD as bash does for a cursor at the end of LINE (blanks
# separate words; ':' and '=' of bash's default COMP_WORDBREAKS are words of their own), calls
# the script's function and prints COMPREPLY, one candidate a line.
#   complete_line.sh SCRIPT FUNCTION LINE
set -u
source "$1" || exit 1
function="$2" line="$3"
COMP_WORDBREAKS=$' \t\n"\'><=;|&(:'
COMP_LINE="$line"
COMP_POINT=${#line}
COMP_WORDS=()
rest="$line"
while [[ -n $rest ]]; do
  case "$rest" in
    [[:space:]]*) rest="${rest#?}" ;;
    [=:]*) COMP_WORDS+=("${rest:0:1}"); rest="${rest#?}" ;;
    *) word="${rest%%[[:space:]=:]*}"; COMP_WORDS+=("$word"); rest="${rest#"$word"}" ;;
  esac
done
[[ -z $line || $line == *[[:space:]] ]] && COMP_WORDS+=("")
COMP_CWORD=$(( ${#COMP_WORDS[@]} - 1 ))
COMPREPLY=()
"$function" || exit 1
(( ${#COMPREPLY[@]} )) && printf '%s\n' "${COMPREPLY[@]}"
exit 0
