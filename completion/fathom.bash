# bash completion for fathom: options (from fathom --help), scene names (--list-scenes), formula
# names (--list-formulas), the subcommands, and file names where an option takes a file.
# Installed by `cmake --install` into share/bash-completion/completions/fathom; or: source this file.
_fathom()
{
    local cur prev fathom
    cur=${COMP_WORDS[COMP_CWORD]}
    prev=${COMP_WORDS[COMP_CWORD - 1]}
    fathom=${COMP_WORDS[0]}
    case $prev in
    --scene)
        COMPREPLY=($(compgen -W "$("$fathom" --list-scenes 2>/dev/null | awk '{print $1}')" -- "$cur") $(compgen -f -X '!*.@(json|fathom|png|exr)' -- "$cur"))
        return ;;
    --formula | --help-formula | check-formula)
        COMPREPLY=($(compgen -W "$("$fathom" --list-formulas 2>/dev/null | awk '{print $1}')" -- "$cur") $(compgen -f -X '!*.glsl' -- "$cur"))
        return ;;
    --quality) COMPREPLY=($(compgen -W "draft interactive final reference" -- "$cur")); return ;;
    --backend) COMPREPLY=($(compgen -W "auto fragment compute" -- "$cur")); return ;;
    --truth) COMPREPLY=($(compgen -W "model path" -- "$cur")); return ;;
    --video) COMPREPLY=($(compgen -W "codec=h264 codec=av1 codec=vp9 crf= pix_fmt=yuv420p pix_fmt=yuv444p" -- "$cur")); return ;;
    --dem | --output | --path) COMPREPLY=($(compgen -f -- "$cur")); return ;;
    --out) COMPREPLY=($(compgen -d -- "$cur")); return ;;
    esac
    if [ "$COMP_CWORD" -eq 1 ] && [[ $cur != -* ]]; then
        COMPREPLY=($(compgen -W "bench render stitch check-formula mesh" -- "$cur"))
        return
    fi
    COMPREPLY=($(compgen -W "$("$fathom" --help 2>/dev/null | grep -oE -- '--[a-z][a-z-]+' | sort -u)" -- "$cur"))
}
complete -F _fathom fathom
