namespace oscidrum::io {}
