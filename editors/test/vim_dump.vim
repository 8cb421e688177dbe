" Writes the syntax group of every non-blank byte of the files given as
" arguments, as seen by editors/vim, to the file g:out:
"   FILE path
"   LINE:BYTE_COLUMN:GROUP:LINKED_GROUP
" Usage: vim -Nu NONE -i NONE -es --cmd 'let g:out="OUT"' -S vim_dump.vim FILE...
let &runtimepath = expand('<sfile>:p:h:h') . '/vim,' . &runtimepath
filetype plugin on
syntax on
let s:out = []
for s:file in argv()
  execute 'edit ' . fnameescape(s:file)
  call add(s:out, 'FILE ' . s:file . ' ' . &filetype)
  for s:l in range(1, line('$'))
    let s:text = getline(s:l)
    for s:c in range(1, len(s:text))
      if s:text[s:c - 1] !~# '\s'
        let s:id = synID(s:l, s:c, 1)
        call add(s:out, s:l . ':' . s:c . ':' . synIDattr(s:id, 'name') . ':' . synIDattr(synIDtrans(s:id), 'name'))
      endif
    endfor
  endfor
endfor
call writefile(s:out, g:out)
qall!
