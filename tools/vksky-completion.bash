# bash completion for vksky (installed as share/bash-completion/completions/vksky).
# Flags come from `vksky --help` and shipped scene names from `vksky --list-scenes`, so the completion never goes
# out of date with the binary it completes.
_vksky()
{
    local cur prev
    cur=${COMP_WORDS[COMP_CWORD]}
    prev=${COMP_WORDS[COMP_CWORD-1]}
    local exe=${COMP_WORDS[0]}
    case $prev in
        --render) COMPREPLY=($(compgen -f -X '!*.@(exr|png)' -- "$cur") $(compgen -d -- "$cur")); compopt -o filenames 2>/dev/null; return ;;
        --screenshot) COMPREPLY=($(compgen -f -X '!*.png' -- "$cur") $(compgen -d -- "$cur")); compopt -o filenames 2>/dev/null; return ;;
        --scene)
            local names
            names=$("$exe" --list-scenes 2>/dev/null | awk '{print $1}')
            COMPREPLY=($(compgen -W "$names" -- "$cur") $(compgen -f -X '!*.@(json|exr)' -- "$cur") $(compgen -d -- "$cur"))
            compopt -o filenames 2>/dev/null; return ;;
        --tonemap) COMPREPLY=($(compgen -W "clamp reinhard aces" -- "$cur")); return ;;
        --quality) COMPREPLY=($(compgen -W "low medium high ultra" -- "$cur")); return ;;
        --sky-mode) COMPREPLY=($(compgen -W "march skyview auto fill" -- "$cur")); return ;;
        --sky-pass) COMPREPLY=($(compgen -W "fragment compute auto" -- "$cur")); return ;;
        --lut-format) COMPREPLY=($(compgen -W "f16 f32" -- "$cur")); return ;;
        --units) COMPREPLY=($(compgen -W "photometric relative" -- "$cur")); return ;;
        --exr-type) COMPREPLY=($(compgen -W "half float auto" -- "$cur")); return ;;
        --mie-phase) COMPREPLY=($(compgen -W "hg cornette-shanks henyey-greenstein" -- "$cur")); return ;;
        --date) COMPREPLY=($(compgen -W "$(date +%F)" -- "$cur")); return ;;
        --time) COMPREPLY=($(compgen -W "$(date +%H:%M)" -- "$cur")); return ;;
        --animate)   # PARAM= of the common ones (any numeric flag works); the user types FROM:TO
            COMPREPLY=($(compgen -W "time= sun-elevation= sun-azimuth= yaw= pitch= fov= altitude= exposure= mie-g= mie-scale= rayleigh-scale=" -- "$cur"))
            compopt -o nospace 2>/dev/null; return ;;
    esac
    # A flag that takes a value: nothing sensible to offer beyond what the user types.
    if [[ $prev == --* ]] && "$exe" --help 2>/dev/null | grep -qE "^ +$prev +[A-Z]"; then
        COMPREPLY=()
        return
    fi
    if [[ $cur == -* || -z $cur ]]; then
        local flags
        flags=$("$exe" --help 2>/dev/null | grep -oE '^ +--[a-z0-9-]+' | tr -d ' ')
        COMPREPLY=($(compgen -W "$flags" -- "$cur"))
    fi
}
complete -F _vksky vksky
