" CSF physics scenes (csf(5))
autocmd BufNewFile,BufRead *.csf setfiletype csf
